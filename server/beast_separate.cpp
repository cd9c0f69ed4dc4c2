// Asio's and Beast's compiled parts (the HTTP parser, the WebSocket handshake, permessage-deflate,
// error categories, Asio's scheduler and sockets), once for the whole program instead of inline
// in every file that includes them: BOOST_{ASIO,BEAST}_SEPARATE_COMPILATION, set on every user
// by the tourmap_beast target (server/CMakeLists.txt). Measured 2026-11-29: ws_session.cpp took
// 23 % less CPU to compile under the sanitizers (80.9 -> 62.3 s).
#include <boost/asio/impl/src.hpp>
#include <boost/beast/src.hpp>

# Fails the web build with a clear message when web/node_modules has not been installed.
# Usage: cmake -D NODE_MODULES=<dir> -P require-node-modules.cmake
if(NOT IS_DIRECTORY "${NODE_MODULES}/vite")
  message(FATAL_ERROR "${NODE_MODULES} is missing or incomplete: run scripts/setup (it runs `npm ci` in web/) "
                      "or configure with -DTOURMAP_BUILD_WEB=OFF to skip the web client.")
endif()

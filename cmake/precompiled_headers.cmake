# Precompiled headers (PCH) for the sanitizer build: the heavy third-party headers that most
# files of a target parse (GoogleTest, nlohmann/json, Eigen), compiled once per target instead of
# once per file. Included from the top-level CMakeLists.txt once every target exists; the targets
# are named here so that their own CMakeLists stay as they are.
#
# Measured 2026-11-29 on the 2-core machine, CPU seconds (user+sys) per file:
# - clang 14, ASan+UBSan, -O1 -gline-tables-only (scripts/test-sanitizers): a test file 1.7-1.9 s
#   less (e.g. 5.8 -> 3.9 s, 16.0 -> 14.2 s), each target's PCH 3-5 s once; ~4 min of CPU over
#   the ~120 test files and the api/crowd libraries.
# - gcc 12, Release -O3 (scripts/build): only ~0.8 s less per test file (5.4 -> 4.5 s, 10.7 ->
#   9.9 s; the optimiser dominates), 5-10 s per PCH, and gcc's PCH makes libstdc++'s inlined code
#   warn in our files (-Warray-bounds on std::string in tests/unit/api/params_test.cpp). Hence
#   TOURMAP_PCH defaults to ON with clang only.
#
# A PCH is force-included ahead of each file's own includes, so it can hide a missing #include.
# The Release build (gcc, no PCH) compiles every file on its own, as before, and catches that;
# -DTOURMAP_PCH=OFF does the same with clang.
if(CMAKE_CXX_COMPILER_ID MATCHES "Clang")
  set(tourmap_pch_default ON)
else()
  set(tourmap_pch_default OFF)
endif()
option(TOURMAP_PCH "Precompile the heavy third-party headers of the big targets (default: with clang)"
       ${tourmap_pch_default})

# tourmap_pch(<target> <header>...): angle-bracket headers, found like the files' own includes
# (in the SYSTEM include directories the target already has, so their warnings stay out).
function(tourmap_pch target)
  if(TOURMAP_PCH AND TARGET ${target})
    set(headers)
    foreach(h IN LISTS ARGN)
      list(APPEND headers "<${h}>")
    endforeach()
    target_precompile_headers(${target} PRIVATE ${headers})
  endif()
endfunction()

# Per target, the headers most of its files parse (from the compile commands with -H): GoogleTest
# in all 120 test files, json in 27 of api's 32 files and all integration tests, Eigen in 21 of
# the crowd library's 22 and 20 of the crowd tests' 21.
tourmap_pch(unit_tests gtest/gtest.h vector string)
tourmap_pch(crowd_tests gtest/gtest.h Eigen/Core Eigen/Geometry vector string)
tourmap_pch(integration_tests gtest/gtest.h nlohmann/json.hpp vector string)
tourmap_pch(tourmap_api nlohmann/json.hpp Eigen/Core vector string)
tourmap_pch(tourmap_crowd Eigen/Core Eigen/Geometry vector string algorithm)

# STRATA_SANITIZE: every target of the project built with AddressSanitizer and
# UndefinedBehaviorSanitizer. Any report ends the process with a non-zero status
# (-fno-sanitize-recover), so a test that triggers one fails; scripts/sanitize.sh runs the unit and
# device tests this way. System libraries (Mesa's lavapipe, the Vulkan loader and validation layer,
# OpenCV, LCM) are not instrumented; their leaks are suppressed by name in
# scripts/sanitizers/lsan.supp, never ours.
#
# STRATA_BUILD_FUZZ: additionally instruments every target for libFuzzer's coverage feedback
# (-fsanitize=fuzzer-no-link) and builds fuzz/ (needs clang: libFuzzer ships with it). One build
# tree then serves both the sanitized tests and the fuzz targets.
if(STRATA_BUILD_FUZZ)
  if(NOT CMAKE_CXX_COMPILER_ID MATCHES "Clang")
    message(FATAL_ERROR "STRATA_BUILD_FUZZ=ON needs clang (libFuzzer): configure with CXX=clang++")
  endif()
  set(STRATA_SANITIZE ON)
endif()
if(STRATA_SANITIZE)
  # -O1 with line tables only, after the build type's flags (the last -O and -g win): the level
  # AddressSanitizer advises, reports still name file and line, and the whole tree compiles about
  # a quarter faster than RelWithDebInfo's -O2 -g (25 s against 34 s for src/strata/odometry/vio_window.cpp
  # with clang 14), which is most of the CI sanitizer stage's time.
  set(strata_sanitize_flags -fsanitize=address,undefined -fno-sanitize-recover=all
                            -fno-omit-frame-pointer -O1)
  if(CMAKE_CXX_COMPILER_ID MATCHES "Clang")
    list(APPEND strata_sanitize_flags -gline-tables-only)
  else()
    list(APPEND strata_sanitize_flags -g1)  # gcc's nearest: functions and lines
  endif()
  if(STRATA_BUILD_FUZZ)
    list(APPEND strata_sanitize_flags -fsanitize=fuzzer-no-link)
  endif()
  add_compile_options(${strata_sanitize_flags})
  add_link_options(-fsanitize=address,undefined)
  message(STATUS "strata: sanitizers on (${strata_sanitize_flags})")
endif()

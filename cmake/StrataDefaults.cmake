# Warnings on from day one; -Werror where STRATA_WERROR is set (CI).
function(strata_set_target_defaults target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wno-missing-field-initializers)
  # NOTE: in a unity batch every source but the first is an included file, and GCC then flags a
  # class of one file holding a type of that file's anonymous namespace (-Wsubobject-linkage),
  # which is harmless where the class is file-local as well.
  if(STRATA_UNITY_BUILD AND CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
    target_compile_options(${target} PRIVATE -Wno-subobject-linkage)
  endif()
  if(STRATA_WERROR)
    target_compile_options(${target} PRIVATE -Werror)
  endif()
  target_compile_features(${target} PUBLIC cxx_std_17)
endfunction()

# strata_library(<target> <name> [ROOT <dir>] [NO_INSTALL]): the conventions of every library:
# ALIAS strata::<name> (the exported name too), includes relative to ROOT (src/ by default, so
# that every header is <strata/<capability>/...> in the tree; include/ after install), warnings,
# and a place in the installed package. Libraries of the programs (apps/) pass ROOT and
# NO_INSTALL.
function(strata_library target name)
  cmake_parse_arguments(ARG "NO_INSTALL" "ROOT" "" ${ARGN})
  if(NOT ARG_ROOT)
    set(ARG_ROOT "${PROJECT_SOURCE_DIR}/src")
  endif()
  add_library(strata::${name} ALIAS ${target})
  set_target_properties(${target} PROPERTIES EXPORT_NAME ${name} POSITION_INDEPENDENT_CODE ON)
  target_include_directories(${target} PUBLIC $<BUILD_INTERFACE:${ARG_ROOT}>
                                              $<INSTALL_INTERFACE:include>)
  strata_set_target_defaults(${target})
  if(NOT ARG_NO_INSTALL)
    set_property(GLOBAL APPEND PROPERTY STRATA_INSTALLED_TARGETS ${target})
  endif()
endfunction()

# cmake --install: the libraries of the engine (and io when built), their public headers under
# include/strata/<capability>/ (internal/ folders stay behind), the embedded shaders (a library of
# SPIR-V words) and a CMake package: find_package(strata CONFIG REQUIRED) gives strata::strata.
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

add_library(strata_all INTERFACE)
add_library(strata::strata ALIAS strata_all)
set_target_properties(strata_all PROPERTIES EXPORT_NAME strata)
target_link_libraries(strata_all INTERFACE strata::mapper)
if(STRATA_BUILD_IO)
  target_link_libraries(strata_all INTERFACE strata::io)
endif()

get_property(strata_targets GLOBAL PROPERTY STRATA_INSTALLED_TARGETS)
install(TARGETS ${strata_targets} strata_shaders strata_all EXPORT strataTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/strata)
foreach(folder core vk map integrate raycast esdf mesh occupancy change select track mapper)
  install(DIRECTORY ${PROJECT_SOURCE_DIR}/engine/${folder}
          DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/strata
          FILES_MATCHING PATTERN "*.h" PATTERN "internal" EXCLUDE)
endforeach()
if(STRATA_BUILD_IO)
  foreach(folder io store align)
    install(DIRECTORY ${PROJECT_SOURCE_DIR}/host/${folder}
            DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/strata
            FILES_MATCHING PATTERN "*.h" PATTERN "internal" EXCLUDE)
  endforeach()
endif()
install(EXPORT strataTargets NAMESPACE strata:: DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/strata)
set(STRATA_CONFIG_WITH_IO ${STRATA_BUILD_IO})
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/strataConfig.cmake.in
                              ${PROJECT_BINARY_DIR}/strataConfig.cmake
                              INSTALL_DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/strata)
write_basic_package_version_file(${PROJECT_BINARY_DIR}/strataConfigVersion.cmake
                                 COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/strataConfig.cmake ${PROJECT_BINARY_DIR}/strataConfigVersion.cmake
        DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/strata)

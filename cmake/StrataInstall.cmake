# cmake --install: every capability's static library, its public headers under
# include/strata/<capability>/ (internal/ folders stay behind), the embedded shaders (a library
# of SPIR-V words inside the mapper component) and a CMake package with one component per
# capability:
#   find_package(strata CONFIG REQUIRED COMPONENTS mapper odometry align objects plan explore sim lcm)
# gives strata::<component> (and the component's other targets), loading the components it needs
# and finding their third-party packages itself (cmake/strataConfig.cmake.in has the table).
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

# strata::strata: the Mapper and the dataset readers, the entry most programs start from.
add_library(strata_all INTERFACE)
add_library(strata::strata ALIAS strata_all)
set_target_properties(strata_all PROPERTIES EXPORT_NAME strata)
target_link_libraries(strata_all INTERFACE strata::mapper)
if(STRATA_BUILD_IO)
  target_link_libraries(strata_all INTERFACE strata::io)
endif()

# Component -> its targets (each a folder of src/strata/ unless noted) and its header folders.
set(strata_component_mapper strata_shaders strata_core strata_vk strata_map strata_integrate
    strata_raycast strata_esdf strata_mesh strata_occupancy strata_change strata_select
    strata_track strata_mapper)
set(strata_headers_mapper core vk map integrate raycast esdf mesh occupancy change select track
    mapper)
set(strata_component_io strata_io)
set(strata_component_trajectory strata_trajectory)
set(strata_component_store strata_store)
set(strata_component_align strata_align strata_localize)
set(strata_headers_align align localize)
set(strata_component_odometry strata_odometry)
set(strata_component_sim strata_sim strata_odometry_synthetic)  # + the odometry's simulated inputs
set(strata_component_eval strata_eval strata_mapper_eval strata_occupancy_eval strata_change_eval
    strata_select_eval strata_objects_eval)
set(strata_headers_eval mapper/eval occupancy/eval change/eval select/eval objects/eval)
set(strata_component_objects strata_objects)
set(strata_component_plan strata_plan)
set(strata_component_explore strata_explore strata_repeat)
set(strata_headers_explore explore repeat)
set(strata_component_lcm strata_lcm_types strata_lcm strata_lcm_objects)
set(strata_all_components mapper io trajectory store align odometry sim eval objects plan explore
    lcm)
# strata::strata belongs with the dataset readers where they are built, else with the Mapper.
if(STRATA_BUILD_IO)
  list(APPEND strata_component_io strata_all)
else()
  list(APPEND strata_component_mapper strata_all)
endif()

set(STRATA_BUILT_COMPONENTS "")
foreach(component ${strata_all_components})
  set(targets "")
  foreach(target ${strata_component_${component}})
    if(TARGET ${target})
      list(APPEND targets ${target})
    endif()
  endforeach()
  if(NOT targets)
    continue()
  endif()
  list(APPEND STRATA_BUILT_COMPONENTS ${component})
  install(TARGETS ${targets} EXPORT strata-${component}
          ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
          INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
  install(EXPORT strata-${component} NAMESPACE strata::
          FILE strata-${component}-targets.cmake
          DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/strata)
  set(folders ${strata_headers_${component}})
  if(NOT folders)
    set(folders ${component})
  endif()
  foreach(folder ${folders})
    # eval/ folders (scoring against the simulator's truth) belong to the eval component.
    get_filename_component(parent ${folder} DIRECTORY)
    set(skip_eval PATTERN "eval" EXCLUDE)
    if(folder MATCHES "/eval$")
      set(skip_eval "")
    endif()
    install(DIRECTORY ${PROJECT_SOURCE_DIR}/src/strata/${folder}
            DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/strata/${parent}
            FILES_MATCHING PATTERN "*.h" PATTERN "internal" EXCLUDE ${skip_eval})
  endforeach()
endforeach()

# Every library must belong to a component: a new one left out of the table above would be
# built but missing from the package.
get_property(strata_targets GLOBAL PROPERTY STRATA_INSTALLED_TARGETS)
foreach(target ${strata_targets})
  set(found FALSE)
  foreach(component ${strata_all_components})
    if(target IN_LIST strata_component_${component})
      set(found TRUE)
    endif()
  endforeach()
  if(NOT found)
    message(FATAL_ERROR "${target} is in no component of the installed package "
                        "(cmake/StrataInstall.cmake)")
  endif()
endforeach()

if(TARGET strata_lcm_types)  # the LCM message headers lcm-gen wrote, as <strata/<type>.hpp>
  install(DIRECTORY ${PROJECT_BINARY_DIR}/src/strata/lcm/generated/strata DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}
          FILES_MATCHING PATTERN "*.hpp")
endif()

configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/strataConfig.cmake.in
                              ${PROJECT_BINARY_DIR}/strataConfig.cmake
                              INSTALL_DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/strata)
write_basic_package_version_file(${PROJECT_BINARY_DIR}/strataConfigVersion.cmake
                                 COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/strataConfig.cmake ${PROJECT_BINARY_DIR}/strataConfigVersion.cmake
        DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/strata)

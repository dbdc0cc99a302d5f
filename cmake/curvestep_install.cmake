# Installs the library headers and exports targets for find_package(curvestep).
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set(_curvestep_libraries)
foreach(layer core protocol gcode)
  if(TARGET curvestep_${layer})
    list(APPEND _curvestep_libraries curvestep_${layer})
    set_target_properties(curvestep_${layer} PROPERTIES EXPORT_NAME ${layer})  # curvestep::core, not curvestep::curvestep_core
    install(DIRECTORY ${PROJECT_SOURCE_DIR}/lib/${layer}/include/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
  endif()
endforeach()
install(TARGETS ${_curvestep_libraries} EXPORT curvestepTargets)
install(EXPORT curvestepTargets NAMESPACE curvestep:: DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/curvestep)

configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/curvestepConfig.cmake.in
  ${PROJECT_BINARY_DIR}/curvestepConfig.cmake
  INSTALL_DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/curvestep)
write_basic_package_version_file(${PROJECT_BINARY_DIR}/curvestepConfigVersion.cmake
  COMPATIBILITY SameMinorVersion ARCH_INDEPENDENT)
install(FILES ${PROJECT_BINARY_DIR}/curvestepConfig.cmake ${PROJECT_BINARY_DIR}/curvestepConfigVersion.cmake
        DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/curvestep)
if(TARGET curvestep)
  install(TARGETS curvestep RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
endif()

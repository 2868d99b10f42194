# `cmake --install build --prefix P` (docs/install.md): the four programs in P/bin, the drawing and
# GIS modules in P/lib/swath (the programs look there, beside themselves), the static libraries in
# P/lib with their headers in P/include, the data in P/share/swath (found from P/bin at run time),
# a CMake package (find_package(swath): swath::planning, swath::fleet, ...) and swath.pc.
# Included from the top-level CMakeLists.txt after every target is defined; the targets' own
# definitions stay as they are: their include folders are rewritten here for the installed tree.
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

# The libraries find_package(swath) gives, swath::<name> for swath_<name>, in dependency order.
set(SWATH_EXPORTED_LIBRARIES
    swath_base swath_geometry swath_vehicle swath_missions swath_planning swath_render swath_energy
    swath_preflight swath_control swath_mavlink swath_fleet swath_worlds swath_fleet_apps)
# The folders whose include/ is public (missions' and planning's MAV_CMD vocabulary is mavlink's).
set(SWATH_HEADER_FOLDERS base geometry vehicle missions planning render energy preflight control
                         mavlink fleet worlds fleet/apps)

# A source folder in INTERFACE_INCLUDE_DIRECTORIES cannot be exported: the build tree's folders
# hold in the build only, P/include once installed.
function(swath_installable_includes target)
  get_target_property(dirs ${target} INTERFACE_INCLUDE_DIRECTORIES)
  set(wrapped "")
  foreach(dir IN LISTS dirs)
    list(APPEND wrapped "$<BUILD_INTERFACE:${dir}>")
  endforeach()
  list(APPEND wrapped "$<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>")
  set_target_properties(${target} PROPERTIES INTERFACE_INCLUDE_DIRECTORIES "${wrapped}")
endfunction()

foreach(library IN LISTS SWATH_EXPORTED_LIBRARIES)
  swath_installable_includes(${library})
  string(REGEX REPLACE "^swath_" "" export_name ${library})
  set_target_properties(${library} PROPERTIES EXPORT_NAME ${export_name})
endforeach()
# Linked privately (LINK_ONLY: its warning options never reach a user of the package).
set_target_properties(swath_warnings PROPERTIES EXPORT_NAME warnings)

install(TARGETS swath swath-energy swath-control swath-fleet RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(TARGETS swath_gis swath_draw LIBRARY DESTINATION lib/swath)
install(TARGETS ${SWATH_EXPORTED_LIBRARIES} swath_warnings EXPORT swathTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR})
foreach(folder IN LISTS SWATH_HEADER_FOLDERS)
  install(DIRECTORY ${PROJECT_SOURCE_DIR}/${folder}/include/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
endforeach()
install(DIRECTORY ${PROJECT_SOURCE_DIR}/share/ DESTINATION ${CMAKE_INSTALL_DATADIR}/swath)

set(SWATH_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/swath)
install(EXPORT swathTargets NAMESPACE swath:: DESTINATION ${SWATH_CMAKE_DIR})
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/swathConfig.cmake.in
                              ${PROJECT_BINARY_DIR}/swathConfig.cmake
                              INSTALL_DESTINATION ${SWATH_CMAKE_DIR})
write_basic_package_version_file(${PROJECT_BINARY_DIR}/swathConfigVersion.cmake
                                 COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/swathConfig.cmake ${PROJECT_BINARY_DIR}/swathConfigVersion.cmake
        DESTINATION ${SWATH_CMAKE_DIR})

# swath.pc: prefix from the file's own place, so a moved tree still works.
file(RELATIVE_PATH SWATH_PC_TO_PREFIX "/prefix/${CMAKE_INSTALL_LIBDIR}/pkgconfig" "/prefix")
configure_file(${PROJECT_SOURCE_DIR}/cmake/swath.pc.in ${PROJECT_BINARY_DIR}/swath.pc @ONLY)
install(FILES ${PROJECT_BINARY_DIR}/swath.pc DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig)

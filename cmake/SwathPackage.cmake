# `cpack -G DEB` in the build folder: swath_<version>_amd64.deb of everything `cmake --install`
# installs, under /usr. Its Depends come from the shared libraries the programs and modules load
# (dpkg-shlibdeps), plus python3 for the module, built for Debian's python3 (its minor version).
set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGE_NAME swath)
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_PACKAGE_VENDOR "swath")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY
    "Drone survey ground control: survey planning, energy, control and fleet simulation")
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_MAINTAINER "swath developers <swath@localhost>")
set(CPACK_DEBIAN_PACKAGE_SECTION science)
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
if(Python3_VERSION_MAJOR AND Python3_VERSION_MINOR)
  math(EXPR swath_next_minor "${Python3_VERSION_MINOR} + 1")
  set(CPACK_DEBIAN_PACKAGE_DEPENDS
      "python3 (>= ${Python3_VERSION_MAJOR}.${Python3_VERSION_MINOR}), python3 (<< ${Python3_VERSION_MAJOR}.${swath_next_minor})")
endif()
include(CPack)

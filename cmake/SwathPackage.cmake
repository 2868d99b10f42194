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
if(SWATH_PYTHON_VERSION)
  string(REGEX REPLACE "^([0-9]+)\\.([0-9]+)$" "\\2" python_minor "${SWATH_PYTHON_VERSION}")
  string(REGEX REPLACE "^([0-9]+)\\.([0-9]+)$" "\\1" python_major "${SWATH_PYTHON_VERSION}")
  math(EXPR python_next_minor "${python_minor} + 1")
  set(CPACK_DEBIAN_PACKAGE_DEPENDS
      "python3 (>= ${SWATH_PYTHON_VERSION}), python3 (<< ${python_major}.${python_next_minor})")
endif()
include(CPack)

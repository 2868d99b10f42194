# `cpack -G DEB` in the build folder: swath_<version>_amd64.deb of everything `cmake --install`
# installs, under /usr. Its Depends come from the shared libraries the programs and modules load
# (dpkg-shlibdeps), plus libzip's package (loaded with dlopen) and python3 for the module, built for Debian's python3 (its minor version).
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
# libzip is loaded with dlopen (missions/src/libzip.hpp), which dpkg-shlibdeps cannot see: the
# package that holds its soname is named here.
set(swath_extra_depends "")
execute_process(COMMAND dpkg-query -S "${SWATH_LIBZIP_SONAME}" OUTPUT_VARIABLE libzip_owner
                ERROR_QUIET RESULT_VARIABLE libzip_owner_status)
if(libzip_owner_status EQUAL 0 AND libzip_owner MATCHES "^([^:, ]+)")
  list(APPEND swath_extra_depends "${CMAKE_MATCH_1}")
endif()
if(SWATH_PYTHON_VERSION)
  string(REGEX REPLACE "^([0-9]+)\\.([0-9]+)$" "\\2" python_minor "${SWATH_PYTHON_VERSION}")
  string(REGEX REPLACE "^([0-9]+)\\.([0-9]+)$" "\\1" python_major "${SWATH_PYTHON_VERSION}")
  math(EXPR python_next_minor "${python_minor} + 1")
  list(APPEND swath_extra_depends "python3 (>= ${SWATH_PYTHON_VERSION})"
       "python3 (<< ${python_major}.${python_next_minor})")
endif()
list(JOIN swath_extra_depends ", " CPACK_DEBIAN_PACKAGE_DEPENDS)
include(CPack)

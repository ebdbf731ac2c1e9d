# `make package`: build/ptnet_<version>_amd64.deb (CPack) holding what
# cmake/install.cmake installs, under /usr. Depends: the Debian packages of
# the shared libraries it links (dpkg-shlibdeps) and the module's Python and
# NumPy; Recommends: what find_package(ptnet) and ptnet_torch need (apt
# installs Recommends unless told not to).
#   sudo apt install ./build/ptnet_*.deb     sudo apt remove ptnet
set(PTNET_PACKAGE_MAINTAINER "ptnet maintainers <maintainers@users.noreply.h-seed-f9999840.example>"
    CACHE STRING "The .deb's Maintainer field")

set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGE_NAME ptnet)
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "PressureTransferNet: pressure-mat recordings simulated for any body and transferred between bodies")
set(CPACK_PACKAGE_DESCRIPTION
    "ptnet simulates 80 x 28 ground-pressure-mat recordings from motion capture retargeted onto bodies of any sex, height and weight, and trains and runs an encoder-decoder that transfers a pressure sequence from one body to another (Table 2 and Table 3 of the paper). The command ptnet, the shared library libptnet with its headers and CMake package (find_package(ptnet) -> ptnet::ptnet), and the Python modules ptnet and ptnet_torch for /usr/bin/python3.")
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)  # ptnet_<version>_<arch>.deb
set(CPACK_DEBIAN_PACKAGE_MAINTAINER ${PTNET_PACKAGE_MAINTAINER})
set(CPACK_DEBIAN_PACKAGE_SECTION science)
set(CPACK_STRIP_FILES ON)
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
set(CPACK_DEBIAN_PACKAGE_GENERATE_SHLIBS ON)  # DEBIAN/shlibs for libptnet.so.0.1
if(PTNET_PYTHON_VERSION)
  string(REGEX REPLACE "^3\\.([0-9]+)$" "\\1" minor ${PTNET_PYTHON_VERSION})
  math(EXPR next_minor "${minor} + 1")
  set(CPACK_DEBIAN_PACKAGE_DEPENDS "python3 (>= ${PTNET_PYTHON_VERSION}~), python3 (<< 3.${next_minor}), python3-numpy")
endif()
set(CPACK_DEBIAN_PACKAGE_RECOMMENDS "libtorch-dev, libeigen3-dev, nlohmann-json3-dev, python3-torch")
set(CPACK_DEBIAN_PACKAGE_SUGGESTS "python3-h5py")
# Byte-compile ptnet_torch.py on install and remove the .pyc on removal (as dh_python3 does).
set(CPACK_DEBIAN_PACKAGE_CONTROL_EXTRA ${PROJECT_SOURCE_DIR}/cmake/debian/postinst ${PROJECT_SOURCE_DIR}/cmake/debian/prerm)
set(CPACK_DEBIAN_PACKAGE_CONTROL_STRICT_PERMISSION ON)
# ldconfig from a trigger instead of CPack's postrm, so that `apt remove` leaves nothing.
set(CPACK_POST_BUILD_SCRIPTS ${PROJECT_SOURCE_DIR}/cmake/debian/ldconfig_trigger.cmake)
# Only what is built for installing (make package builds `installables`), not the tests.
set(CMAKE_SKIP_INSTALL_ALL_DEPENDENCY ON)
include(CPack)

# What `cmake --install` (make install PREFIX=..., the .deb of
# cmake/package.cmake) puts where, under the prefix:
#
#   bin/ptnet                          the command (app/)
#   libexec/ptnet/ptnet-torch          its LibTorch half; bin/ptnet runs it (app/ptnet.cpp)
#   lib/<multiarch>/libptnet.so.0.1    every stage in one shared library, SONAME libptnet.so.0.1
#   lib/<multiarch>/cmake/ptnet/       find_package(ptnet 0.1) -> ptnet::ptnet
#   include/ptnet/                     the public headers
#   <site folder>/ptnet.cpython-*.so   the Python module, and python/ptnet_torch.py beside it
#   share/man/man1/                    ptnet(1) and ptnet-<command>(1), from the --help texts
#   share/doc/ptnet/                   README.md and docs/
#
# The executables and the Python module link the stages' static libraries as
# in the build folder (bin/ptnet must not load LibTorch, which libptnet.so
# links); libptnet.so is for other programs (examples/).

# Debian's multiarch library folder for any prefix (ld.so searches
# /usr/local/lib/<multiarch> too), so that the .deb's /usr and a
# `make install` agree.
if(CMAKE_LIBRARY_ARCHITECTURE)
  set(CMAKE_INSTALL_LIBDIR lib/${CMAKE_LIBRARY_ARCHITECTURE} CACHE PATH "Object code libraries (lib/<multiarch>)")
endif()
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

# The targets `make install` and `make package` build (not the tests).
add_custom_target(installables)

# --- the executables: bin/ptnet finds ptnet-torch at this path from bin/.
file(RELATIVE_PATH torch_from_bindir ${CMAKE_INSTALL_FULL_BINDIR} ${CMAKE_INSTALL_FULL_LIBEXECDIR}/ptnet/ptnet-torch)
target_compile_definitions(ptnet PRIVATE PTNET_TORCH_FROM_BINDIR="${torch_from_bindir}")
install(TARGETS ptnet RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(TARGETS ptnet-torch RUNTIME DESTINATION ${CMAKE_INSTALL_LIBEXECDIR}/ptnet)
add_dependencies(installables ptnet)

# --- libptnet.so: the objects of every stage; their own libraries (HDF5, PNG,
# LibTorch, ...) linked privately. What a user of the public headers needs:
# the headers' includes (Eigen, nlohmann/json, LibTorch for model.hpp).
set(stage_objects "")
foreach(stage ${PTNET_STAGES})
  list(APPEND stage_objects $<TARGET_OBJECTS:${stage}>)
endforeach()
add_library(ptnet_shared SHARED ${stage_objects})
add_library(ptnet::ptnet ALIAS ptnet_shared)
set_target_properties(ptnet_shared PROPERTIES
  OUTPUT_NAME ptnet EXPORT_NAME ptnet LIBRARY_OUTPUT_DIRECTORY ${CMAKE_BINARY_DIR}/lib
  # 0.x: no ABI promise between minor versions, so the SONAME carries the minor.
  VERSION ${PROJECT_VERSION} SOVERSION ${PROJECT_VERSION_MAJOR}.${PROJECT_VERSION_MINOR})
target_link_libraries(ptnet_shared PRIVATE ${PTNET_STAGES})  # their libraries; their objects are in already
target_link_libraries(ptnet_shared INTERFACE Eigen3::Eigen nlohmann_json::nlohmann_json Threads::Threads torch)
target_include_directories(ptnet_shared INTERFACE $<BUILD_INTERFACE:${PROJECT_SOURCE_DIR}/include>
                                                  $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
target_compile_features(ptnet_shared INTERFACE cxx_std_17)
add_dependencies(installables ptnet_shared)

set(cmake_dir ${CMAKE_INSTALL_LIBDIR}/cmake/ptnet)
install(TARGETS ptnet_shared EXPORT ptnetTargets LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR})
install(DIRECTORY include/ptnet DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(EXPORT ptnetTargets NAMESPACE ptnet:: DESTINATION ${cmake_dir})
configure_package_config_file(cmake/ptnetConfig.cmake.in ${CMAKE_BINARY_DIR}/ptnetConfig.cmake
                              INSTALL_DESTINATION ${cmake_dir})
write_basic_package_version_file(${CMAKE_BINARY_DIR}/ptnetConfigVersion.cmake COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_BINARY_DIR}/ptnetConfig.cmake ${CMAKE_BINARY_DIR}/ptnetConfigVersion.cmake
        DESTINATION ${cmake_dir})

# --- the Python module and ptnet_torch.py. Their folder is chosen when
# installing, from the prefix the install runs with:
#   /usr         lib/python3/dist-packages      Debian's packaged modules (the .deb)
#   /usr/local   lib/python3.X/dist-packages    Debian's python3 looks there too
#   any other    lib/python3.X/site-packages    as ~/.local and virtual environments
#                                               (PYTHONPATH=PREFIX/lib/python3.X/site-packages)
if(PTNET_PYTHON_EXECUTABLE)
  set(Python_EXECUTABLE ${PTNET_PYTHON_EXECUTABLE})  # python/CMakeLists.txt
endif()
find_package(Python COMPONENTS Interpreter)  # also for the man pages below
if(TARGET ptnet_python)
  set(PTNET_PYTHON_VERSION ${Python_VERSION_MAJOR}.${Python_VERSION_MINOR} CACHE INTERNAL "the module's Python")
  set(PTNET_PYTHON_INSTALL_DIR "" CACHE STRING "The Python module's folder under the prefix (empty: from the prefix)")
  install(CODE "
    set(ptnet_python_dir \"${PTNET_PYTHON_INSTALL_DIR}\")
    if(NOT ptnet_python_dir AND CMAKE_INSTALL_PREFIX MATCHES \"^/usr/?$\")
      set(ptnet_python_dir lib/python3/dist-packages)
    elseif(NOT ptnet_python_dir AND CMAKE_INSTALL_PREFIX MATCHES \"^/usr/local/?$\")
      set(ptnet_python_dir lib/python${PTNET_PYTHON_VERSION}/dist-packages)
    elseif(NOT ptnet_python_dir)
      set(ptnet_python_dir lib/python${PTNET_PYTHON_VERSION}/site-packages)
    endif()")
  install(TARGETS ptnet_python LIBRARY DESTINATION "\${ptnet_python_dir}")
  install(FILES python/ptnet_torch.py DESTINATION "\${ptnet_python_dir}")
  add_dependencies(installables ptnet_python)
endif()

# --- man pages, made from the built command's --help texts (gzipped).
if(Python_Interpreter_FOUND)
  set(man_dir ${CMAKE_BINARY_DIR}/man)
  add_custom_command(OUTPUT ${man_dir}/ptnet.1.gz
    COMMAND ${Python_EXECUTABLE} ${PROJECT_SOURCE_DIR}/cmake/man_pages.py $<TARGET_FILE:ptnet> ${PROJECT_VERSION} ${man_dir}
    DEPENDS ptnet ptnet-torch ${PROJECT_SOURCE_DIR}/cmake/man_pages.py
    COMMENT "Man pages from ptnet --help")
  add_custom_target(man_pages ALL DEPENDS ${man_dir}/ptnet.1.gz)
  add_dependencies(installables man_pages)
  install(DIRECTORY ${man_dir}/ DESTINATION ${CMAKE_INSTALL_MANDIR}/man1 FILES_MATCHING PATTERN "*.1.gz")
endif()

# --- docs: the README and docs/ (the README's links stay relative).
install(FILES README.md DESTINATION ${CMAKE_INSTALL_DOCDIR})
install(DIRECTORY docs/ DESTINATION ${CMAKE_INSTALL_DOCDIR}/docs)

# --- the test of all this (label install): installed into a fresh prefix,
# examples/ built against it, the Python modules imported from it.
if(PTNET_BUILD_TESTS)
  set(python "")
  if(TARGET ptnet_python)
    set(python ${PTNET_PYTHON_EXECUTABLE})
  endif()
  add_test(NAME install COMMAND ${PROJECT_SOURCE_DIR}/tests/install_test.sh ${PROJECT_SOURCE_DIR} ${CMAKE_BINARY_DIR}
                                ${CMAKE_BINARY_DIR}/install_test ${python})
  set_tests_properties(install PROPERTIES LABELS install)
endif()

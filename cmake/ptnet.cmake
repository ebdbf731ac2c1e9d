# Helpers shared by the stage folders.
#
# ptnet_stage(NAME SOURCES... DEPENDS stage... [TORCH])
#   defines the static library ptnet_<NAME> (alias ptnet::<NAME>) from the
#   listed sources, with include/ public, linking the named earlier stages.
set(PTNET_STAGES "" CACHE INTERNAL "stage libraries defined so far")

function(ptnet_stage name)
  cmake_parse_arguments(S "TORCH" "" "SOURCES;DEPENDS;LIBS" ${ARGN})
  if(NOT S_SOURCES)
    message(STATUS "ptnet: stage ${name} has no sources yet; skipped")
    return()
  endif()
  add_library(ptnet_${name} STATIC ${S_SOURCES})
  add_library(ptnet::${name} ALIAS ptnet_${name})
  target_include_directories(ptnet_${name} PUBLIC ${PROJECT_SOURCE_DIR}/include
                                           PRIVATE ${PROJECT_SOURCE_DIR}/src)
  target_compile_options(ptnet_${name} PRIVATE ${PTNET_WARNINGS})
  # The shared library libptnet.so (cmake/install.cmake) and the Python module
  # are made of the stages' objects: position-independent code.
  set_target_properties(ptnet_${name} PROPERTIES POSITION_INDEPENDENT_CODE ON)
  target_compile_definitions(ptnet_${name} PUBLIC PTNET_VERSION="${PROJECT_VERSION}")
  target_link_libraries(ptnet_${name} PUBLIC Eigen3::Eigen nlohmann_json::nlohmann_json Threads::Threads)
  foreach(dep ${S_DEPENDS})
    target_link_libraries(ptnet_${name} PUBLIC ptnet_${dep})
  endforeach()
  if(S_LIBS)
    target_link_libraries(ptnet_${name} PUBLIC ${S_LIBS})
  endif()
  if(S_TORCH)
    target_link_libraries(ptnet_${name} PUBLIC ${TORCH_LIBRARIES})
  endif()
  set(PTNET_STAGES ${PTNET_STAGES} ptnet_${name} CACHE INTERNAL "")
endfunction()

# ptnet_test(FILE LABELS label...) : one GoogleTest executable per test file,
# linked against every stage; its tests are registered with CTest and labelled.
function(ptnet_test file)
  cmake_parse_arguments(T "" "" "LABELS" ${ARGN})
  get_filename_component(name ${file} NAME_WE)
  add_executable(${name} ${file})
  target_link_libraries(${name} PRIVATE ${PTNET_STAGES} GTest::gtest GTest::gtest_main)
  # Tests reach a stage's internals (src/<stage>/*.hpp) through the stages'
  # private include path: #include "train/window_index.hpp".
  target_include_directories(${name} PRIVATE ${PROJECT_SOURCE_DIR}/tests ${PROJECT_SOURCE_DIR}/src)
  target_compile_definitions(${name} PRIVATE
    PTNET_TEST_DATA="${PROJECT_SOURCE_DIR}/tests/data"
    PTNET_SHARED_MOCAP="${PROJECT_SOURCE_DIR}/../shared/mocap"
    PTNET_SHARED_CORPUS="${PROJECT_SOURCE_DIR}/../shared/mocap-corpus"
    PTNET_BINARY="$<TARGET_FILE:ptnet>")
  if(NOT T_LABELS)
    set(T_LABELS unit)
  endif()
  gtest_discover_tests(${name} PROPERTIES LABELS "${T_LABELS}" DISCOVERY_TIMEOUT 60)
endfunction()

# Helpers shared by the stage folders.
#
# ptnet_stage(NAME SOURCES... HEADERS h... DEPENDS stage... [TORCH] [LIBS lib...])
#   defines the static library ptnet_<NAME> (alias ptnet::<NAME>) from the
#   listed sources, with include/ public, linking the named earlier stages.
#   HEADERS: the public headers the stage owns (include/ptnet/<h>.hpp, named
#   without the folder and extension; by default <NAME>.hpp and <NAME>_*.hpp).
#   DEPENDS: every stage whose public or
#   private headers its sources, private headers or public headers include
#   (directly or through another declared stage); ptnet_check_stage_includes()
#   holds the stages to that at configure time.
set(PTNET_STAGES "" CACHE INTERNAL "stage libraries defined so far")
set(PTNET_STAGE_TABLE "" CACHE INTERNAL "per stage: name|depends|headers|files, for the include check")

# ptnet_unity(TARGET): compile TARGET's sources in batches of
# PTNET_UNITY_BATCH (PTNET_UNITY_BUILD, the top CMakeLists.txt). The files of
# a target share their anonymous namespaces then: two files of one stage may
# not define the same internal name.
function(ptnet_unity target)
  set_target_properties(${target} PROPERTIES UNITY_BUILD ${PTNET_UNITY_BUILD}
                                             UNITY_BUILD_BATCH_SIZE ${PTNET_UNITY_BATCH})
endfunction()

function(ptnet_stage name)
  cmake_parse_arguments(S "TORCH" "" "SOURCES;HEADERS;DEPENDS;LIBS" ${ARGN})
  if(NOT S_SOURCES)
    message(STATUS "ptnet: stage ${name} has no sources yet; skipped")
    return()
  endif()
  foreach(dep ${S_DEPENDS})
    if(NOT TARGET ptnet_${dep})
      message(FATAL_ERROR "ptnet: stage ${name} depends on '${dep}', which is not a stage defined before it "
                          "(the stage order: the top CMakeLists.txt)")
    endif()
  endforeach()
  # What the include check reads: the sources, the stage's private headers
  # (src/<stage>/*.hpp) and the public headers it owns, as absolute paths.
  set(files "")
  foreach(f ${S_SOURCES})
    get_filename_component(f ${f} ABSOLUTE BASE_DIR ${CMAKE_CURRENT_SOURCE_DIR})
    list(APPEND files ${f})
  endforeach()
  file(GLOB private_headers ${CMAKE_CURRENT_SOURCE_DIR}/*.hpp)
  list(APPEND files ${private_headers})
  if(NOT S_HEADERS)  # by default: include/ptnet/<name>.hpp and <name>_*.hpp
    file(GLOB own RELATIVE ${PROJECT_SOURCE_DIR}/include/ptnet ${PROJECT_SOURCE_DIR}/include/ptnet/${name}.hpp
                                                                ${PROJECT_SOURCE_DIR}/include/ptnet/${name}_*.hpp)
    string(REPLACE ".hpp" "" S_HEADERS "${own}")
  endif()
  foreach(h ${S_HEADERS})
    if(NOT EXISTS ${PROJECT_SOURCE_DIR}/include/ptnet/${h}.hpp)
      message(FATAL_ERROR "ptnet: stage ${name} lists header '${h}': include/ptnet/${h}.hpp does not exist")
    endif()
    list(APPEND files ${PROJECT_SOURCE_DIR}/include/ptnet/${h}.hpp)
  endforeach()
  string(REPLACE ";" "," deps_text "${S_DEPENDS}")
  string(REPLACE ";" "," headers_text "${S_HEADERS}")
  string(REPLACE ";" "," files_text "${files}")
  set(PTNET_STAGE_TABLE ${PTNET_STAGE_TABLE} "${name}|${deps_text}|${headers_text}|${files_text}" CACHE INTERNAL "")
  add_library(ptnet_${name} STATIC ${S_SOURCES})
  add_library(ptnet::${name} ALIAS ptnet_${name})
  target_include_directories(ptnet_${name} PUBLIC ${PROJECT_SOURCE_DIR}/include
                                           PRIVATE ${PROJECT_SOURCE_DIR}/src)
  target_compile_options(ptnet_${name} PRIVATE ${PTNET_WARNINGS})
  # The shared library libptnet.so (cmake/install.cmake) and the Python module
  # are made of the stages' objects: position-independent code.
  set_target_properties(ptnet_${name} PROPERTIES POSITION_INDEPENDENT_CODE ON)
  ptnet_unity(ptnet_${name})
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
  target_link_libraries(${name} PRIVATE ${PTNET_STAGES} ptnet_test_support GTest::gtest GTest::gtest_main)
  # Tests reach a stage's internals (src/<stage>/*.hpp) through the stages'
  # private include path: #include "train/window_index.hpp".
  target_include_directories(${name} PRIVATE ${PROJECT_SOURCE_DIR}/tests ${PROJECT_SOURCE_DIR}/src)
  target_compile_definitions(${name} PRIVATE
    PTNET_TEST_DATA="${PROJECT_SOURCE_DIR}/tests/data"
    PTNET_SHARED_MOCAP="${PROJECT_SOURCE_DIR}/../shared/mocap"
    PTNET_SHARED_CORPUS="${PROJECT_SOURCE_DIR}/../shared/mocap-corpus"
    PTNET_SHARED_GAIT="${PROJECT_SOURCE_DIR}/../shared/real-gait"
    PTNET_SOURCE_DIR="${PROJECT_SOURCE_DIR}"
    PTNET_BINARY="$<TARGET_FILE:ptnet>")
  if(NOT T_LABELS)
    set(T_LABELS unit)
  endif()
  # gtest_discover_tests passes its properties on as a flat list, so a
  # second label would be read as a property name: it gets the first, and an
  # include file run after the discovered tests' (TEST_INCLUDE_FILES keeps
  # the order) sets them all on the test names it listed in ${name}_TESTS.
  list(GET T_LABELS 0 first)
  gtest_discover_tests(${name} PROPERTIES LABELS ${first} DISCOVERY_TIMEOUT 60)
  list(LENGTH T_LABELS count)
  if(count GREATER 1)
    set(labels_file ${CMAKE_CURRENT_BINARY_DIR}/${name}_labels.cmake)
    file(WRITE ${labels_file} "if(${name}_TESTS)\n  set_tests_properties(\${${name}_TESTS} PROPERTIES LABELS \"${T_LABELS}\")\nendif()\n")
    set_property(DIRECTORY APPEND PROPERTY TEST_INCLUDE_FILES ${labels_file})
  endif()
endfunction()

# ptnet_check_stage_includes(): after every stage is defined. Writes the
# stage table to the build folder, runs cmake/check_stage_includes.cmake on
# it (configuring fails when a stage's files include a header of a stage it
# does not declare, directly or through its declared stages, or when a
# public header belongs to no stage) and registers the same check as the
# test `stage_includes` (label unit), which catches an include added since
# the last configure.
function(ptnet_check_stage_includes)
  set(table_file ${CMAKE_BINARY_DIR}/ptnet_stage_table.cmake)
  set(text "set(PTNET_CHECK_SOURCE_DIR \"${PROJECT_SOURCE_DIR}\")\nset(PTNET_CHECK_TABLE\n")
  foreach(row ${PTNET_STAGE_TABLE})
    string(APPEND text "  \"${row}\"\n")
  endforeach()
  string(APPEND text ")\n")
  file(WRITE ${table_file} "${text}")
  set(PTNET_STAGE_TABLE_FILE ${table_file})
  include(${PROJECT_SOURCE_DIR}/cmake/check_stage_includes.cmake)
  if(PTNET_BUILD_TESTS)
    add_test(NAME stage_includes
             COMMAND ${CMAKE_COMMAND} -DPTNET_STAGE_TABLE_FILE=${table_file}
                     -P ${PROJECT_SOURCE_DIR}/cmake/check_stage_includes.cmake)
    set_tests_properties(stage_includes PROPERTIES LABELS unit)
  endif()
endfunction()

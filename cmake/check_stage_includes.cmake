# The stages' includes against their DEPENDS (cmake/ptnet.cmake,
# ptnet_stage). Run at configure time by ptnet_check_stage_includes() and
# as the test `stage_includes`:
#   cmake -DPTNET_STAGE_TABLE_FILE=build/ptnet_stage_table.cmake -P cmake/check_stage_includes.cmake
#
# The table (written at configure time) gives per stage its name, its
# declared DEPENDS, the public headers it owns (HEADERS) and its files: its
# sources, its private headers src/<stage>/*.hpp and its public headers.
# Every `#include "ptnet/<h>.hpp"` (or <...>) in a stage's files must name a
# header owned by the stage itself or by a stage it declares, directly or
# through the DEPENDS of the stages it declares; so must every include of
# another stage's private header ("<stage>/<h>.hpp"). Every public header
# must be owned by exactly one stage. Failures are one line each, naming the
# file, the header and the stage that would have to be declared (a message
# holds no ';', which would split the list of problems).
cmake_minimum_required(VERSION 3.18)
if(NOT PTNET_STAGE_TABLE_FILE)
  message(FATAL_ERROR "check_stage_includes: pass -DPTNET_STAGE_TABLE_FILE=<build>/ptnet_stage_table.cmake")
endif()
include(${PTNET_STAGE_TABLE_FILE})  # PTNET_CHECK_SOURCE_DIR, PTNET_CHECK_TABLE

set(_stages "")
set(_problems "")
foreach(_row IN LISTS PTNET_CHECK_TABLE)
  string(REPLACE "|" ";" _parts "${_row}")
  list(GET _parts 0 _name)
  list(GET _parts 1 _deps)
  list(GET _parts 2 _headers)
  list(GET _parts 3 _files)
  string(REPLACE "," ";" _deps "${_deps}")
  string(REPLACE "," ";" _headers "${_headers}")
  string(REPLACE "," ";" _files "${_files}")
  list(APPEND _stages ${_name})
  set(_deps_${_name} ${_deps})
  set(_files_${_name} ${_files})
  foreach(_h ${_headers})
    if(DEFINED _owner_${_h})
      list(APPEND _problems "include/ptnet/${_h}.hpp: listed in HEADERS of two stages, ${_owner_${_h}} and ${_name}")
    endif()
    set(_owner_${_h} ${_name})
  endforeach()
endforeach()

file(GLOB _public RELATIVE ${PTNET_CHECK_SOURCE_DIR}/include/ptnet ${PTNET_CHECK_SOURCE_DIR}/include/ptnet/*.hpp)
foreach(_p ${_public})
  string(REGEX REPLACE "\\.hpp$" "" _h "${_p}")
  if(NOT DEFINED _owner_${_h})
    list(APPEND _problems "include/ptnet/${_p}: belongs to no stage: list ${_h} in HEADERS of the stage that defines it")
  endif()
endforeach()

# The stage and every stage it reaches through declared DEPENDS.
function(_reachable stage out)
  set(todo ${stage})
  set(seen "")
  while(todo)
    list(POP_FRONT todo s)
    if(NOT s IN_LIST seen)
      list(APPEND seen ${s})
      list(APPEND todo ${_deps_${s}})
    endif()
  endwhile()
  set(${out} ${seen} PARENT_SCOPE)
endfunction()

set(_include_regex "^[ \t]*#[ \t]*include[ \t]*[\"<]([A-Za-z0-9_]+)/([A-Za-z0-9_]+)\\.hpp[\">]")
set(_count 0)
foreach(_name ${_stages})
  _reachable(${_name} _allowed)
  foreach(_f ${_files_${_name}})
    math(EXPR _count "${_count} + 1")
    file(RELATIVE_PATH _rel ${PTNET_CHECK_SOURCE_DIR} ${_f})
    if(NOT EXISTS ${_f})
      list(APPEND _problems "${_rel}: listed for stage ${_name} but missing")
      continue()
    endif()
    file(STRINGS ${_f} _lines REGEX "${_include_regex}")
    foreach(_line IN LISTS _lines)
      string(REGEX MATCH "${_include_regex}" _m "${_line}")
      set(_dir ${CMAKE_MATCH_1})
      set(_base ${CMAKE_MATCH_2})
      if(_dir STREQUAL "ptnet")
        if(NOT DEFINED _owner_${_base})
          list(APPEND _problems "${_rel}: includes ptnet/${_base}.hpp, which no stage owns")
          continue()
        endif()
        set(_owner ${_owner_${_base}})
      elseif(_dir IN_LIST _stages)
        set(_owner ${_dir})  # a stage's private header (src/<stage>/<h>.hpp)
      else()
        continue()  # a third-party header (nlohmann/json.hpp, ...)
      endif()
      if(NOT _owner IN_LIST _allowed)
        string(REPLACE ";" " " _declared "${_deps_${_name}}")
        set(_problem "${_rel}: includes ${_dir}/${_base}.hpp of stage ${_owner}, which stage ${_name} does not")
        string(APPEND _problem " declare (DEPENDS ${_declared}): add ${_owner} to DEPENDS in"
                               " src/${_name}/CMakeLists.txt or drop the include")
        list(APPEND _problems "${_problem}")
      endif()
    endforeach()
  endforeach()
endforeach()

if(_problems)
  list(LENGTH _problems _n)
  string(REPLACE ";" "\n  " _text "${_problems}")
  message(FATAL_ERROR "ptnet: ${_n} stage include problem(s):\n  ${_text}")
endif()
list(LENGTH _stages _n)
message(STATUS "ptnet: the includes of ${_n} stages (${_count} files) match their DEPENDS")

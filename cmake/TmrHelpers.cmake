# Helpers that give every tmr target the same warnings, include layout and
# install/export rules.

set(TMR_WARNING_FLAGS -Wall -Wextra -Wno-unused-parameter)

# tmr_add_library(NAME
#   SRCS file...            sources
#   PUBLIC_INCLUDE dir      public include directory (installed, unless
#                           NO_HEADER_INSTALL: another target installs it)
#   PRIVATE_INCLUDE dir...  private include directories
#   PUBLIC_LINK lib...      dependencies that appear in public headers
#   PRIVATE_LINK lib...)    implementation dependencies
function(tmr_add_library name)
  cmake_parse_arguments(ARG "NO_HEADER_INSTALL" "PUBLIC_INCLUDE"
                        "SRCS;PRIVATE_INCLUDE;PUBLIC_LINK;PRIVATE_LINK" ${ARGN})
  add_library(${name} ${ARG_SRCS})
  add_library(tmr::${name} ALIAS ${name})
  target_compile_options(${name} PRIVATE ${TMR_WARNING_FLAGS})
  target_compile_features(${name} PUBLIC cxx_std_17)
  set_target_properties(${name} PROPERTIES POSITION_INDEPENDENT_CODE ON)
  if(ARG_PUBLIC_INCLUDE)
    target_include_directories(${name} PUBLIC
      $<BUILD_INTERFACE:${ARG_PUBLIC_INCLUDE}>
      $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
    if(NOT ARG_NO_HEADER_INSTALL)
      install(DIRECTORY ${ARG_PUBLIC_INCLUDE}/
              DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
    endif()
  endif()
  if(ARG_PRIVATE_INCLUDE)
    target_include_directories(${name} PRIVATE ${ARG_PRIVATE_INCLUDE})
  endif()
  target_link_libraries(${name} PUBLIC ${ARG_PUBLIC_LINK} PRIVATE ${ARG_PRIVATE_LINK})
  install(TARGETS ${name} EXPORT tmrTargets
          ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
          LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
          RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
endfunction()

# tmr_add_executable(NAME SRCS file... LINK lib... [NO_INSTALL])
function(tmr_add_executable name)
  cmake_parse_arguments(ARG "NO_INSTALL" "" "SRCS;LINK" ${ARGN})
  add_executable(${name} ${ARG_SRCS})
  target_compile_options(${name} PRIVATE ${TMR_WARNING_FLAGS})
  target_link_libraries(${name} PRIVATE ${ARG_LINK})
  if(NOT ARG_NO_INSTALL)
    install(TARGETS ${name} RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
  endif()
endfunction()

# tmr_add_test(NAME SRCS file... LINK lib... [LABELS label...])
# A GoogleTest executable whose tests are registered with ctest one by one,
# each labelled `quick` (docs/testing.md) besides LABELS.
function(tmr_add_test name)
  if(NOT TMR_BUILD_TESTS)
    return()
  endif()
  cmake_parse_arguments(ARG "" "" "SRCS;LINK;LABELS;INCLUDE" ${ARGN})
  add_executable(${name} ${ARG_SRCS})
  target_compile_options(${name} PRIVATE ${TMR_WARNING_FLAGS})
  target_include_directories(${name} PRIVATE ${ARG_INCLUDE})
  target_link_libraries(${name} PRIVATE ${ARG_LINK} GTest::gtest GTest::gtest_main)
  gtest_discover_tests(${name}
    WORKING_DIRECTORY ${CMAKE_CURRENT_BINARY_DIR}
    DISCOVERY_TIMEOUT 60)
  # gtest_discover_tests writes a list-valued LABELS property out flat
  # (LABELS a b), and ctest then drops b: the discovered tests
  # (${name}_TESTS) are labelled by a file that ctest reads after gtest's.
  set(labels ${ARG_LABELS} quick)
  set(labels_file ${CMAKE_CURRENT_BINARY_DIR}/${name}_labels.cmake)
  file(WRITE ${labels_file}
    "foreach(test IN LISTS ${name}_TESTS)\n"
    "  set_tests_properties(\"\${test}\" PROPERTIES LABELS \"${labels}\")\n"
    "endforeach()\n")
  set_property(DIRECTORY APPEND PROPERTY TEST_INCLUDE_FILES ${labels_file})
endfunction()

# tmr_label_by_duration(LONG test...): every test that add_test registered
# in this directory gets the label `long` when it is one of LONG (or a
# real-photo test, real_images.*), else `quick` (docs/testing.md).
function(tmr_label_by_duration)
  cmake_parse_arguments(ARG "" "" "LONG" ${ARGN})
  get_property(tests DIRECTORY PROPERTY TESTS)
  foreach(test IN LISTS tests)
    if(test IN_LIST ARG_LONG OR test MATCHES "^real_images\\.")
      set_property(TEST ${test} APPEND PROPERTY LABELS long)
    else()
      set_property(TEST ${test} APPEND PROPERTY LABELS quick)
    endif()
  endforeach()
endfunction()

# tmr_find_colmap(MIN_VERSION MODE): find_package(COLMAP) without a version
# (COLMAP's version file accepts only its exact version), then COLMAP_FOUND
# only for MIN_VERSION or newer. MODE ON: an error otherwise; AUTO: a note.
macro(tmr_find_colmap min_version mode)
  if("${mode}" STREQUAL "ON")
    find_package(COLMAP REQUIRED)
  else()
    find_package(COLMAP QUIET)
  endif()
  if(COLMAP_FOUND AND COLMAP_VERSION VERSION_LESS ${min_version})
    set(_tmr_colmap_message "COLMAP ${COLMAP_VERSION} found in ${COLMAP_DIR}, "
        "tmr needs ${min_version} or newer (tools/setup_dependencies.sh builds 4.1.1)")
    if("${mode}" STREQUAL "ON")
      message(FATAL_ERROR ${_tmr_colmap_message})
    endif()
    message(STATUS ${_tmr_colmap_message})
    set(COLMAP_FOUND FALSE)
  endif()
endmacro()

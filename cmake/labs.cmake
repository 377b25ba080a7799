# wb_add_lab(<lab> <side>): the targets of one lab on one side.
#   side "student"  -> sources from labs/<lab>/,      executable <lab>
#   side "solution" -> sources from solutions/<lab>/,  executable <lab>-solution
# The student-editable files are the .cpp files in labs/<lab>/; the headers in
# labs/<lab>/ are shared by both sides and never edited. Graded tests in
# tests/<lab>/ compile once against each side as <lab>[-solution]-tests.

function(wb_side_dir side out)
  if(side STREQUAL "student")
    set(${out} ${CMAKE_SOURCE_DIR}/labs PARENT_SCOPE)
  else()
    set(${out} ${CMAKE_SOURCE_DIR}/solutions PARENT_SCOPE)
  endif()
endfunction()

function(wb_suffix side out)
  if(side STREQUAL "student")
    set(${out} "" PARENT_SCOPE)
  else()
    set(${out} "-${side}" PARENT_SCOPE)
  endif()
endfunction()

# The library of one lab's student functions on one side.
function(wb_lab_library lab side)
  set(target ${lab}_${side})
  if(TARGET ${target})
    return()
  endif()
  wb_side_dir(${side} dir)
  # The file list is the student's: the same names on both sides.
  file(GLOB student_files CONFIGURE_DEPENDS ${CMAKE_SOURCE_DIR}/labs/${lab}/*.cpp)
  set(sources)
  foreach(f IN LISTS student_files)
    get_filename_component(name ${f} NAME)
    if(NOT EXISTS ${dir}/${lab}/${name})
      message(FATAL_ERROR "${dir}/${lab}/${name} is missing (labs/${lab}/${name} has no counterpart)")
    endif()
    list(APPEND sources ${dir}/${lab}/${name})
  endforeach()
  add_library(${target} STATIC ${sources})
  target_include_directories(${target} PUBLIC ${CMAKE_SOURCE_DIR}/labs/${lab})
  target_link_libraries(${target} PUBLIC wb_core)
  foreach(dep IN LISTS WB_LAB_DEPS_${lab})
    wb_lab_library(${dep} ${side})
    target_link_libraries(${target} PUBLIC ${dep}_${side})
  endforeach()
endfunction()

function(wb_add_lab lab side)
  wb_lab_library(${lab} ${side})
  wb_suffix(${side} suffix)
  set(exe ${lab}${suffix})
  add_executable(${exe} ${CMAKE_SOURCE_DIR}/framework/drivers/${lab}.cpp)
  # Scene forces call the forces lab's functions of the same side.
  set(forces_lib forces_${side})
  wb_lab_library(forces ${side})
  target_link_libraries(${exe} PRIVATE ${lab}_${side} wb_scene_forces ${forces_lib} wb_core)
  target_compile_definitions(${exe} PRIVATE WB_LAB="${lab}" WB_SIDE="${side}")

  if(WB_TESTS AND EXISTS ${CMAKE_SOURCE_DIR}/tests/${lab})
    file(GLOB test_sources CONFIGURE_DEPENDS ${CMAKE_SOURCE_DIR}/tests/${lab}/*.cpp)
    if(NOT test_sources)
      return()
    endif()
    set(tests ${lab}${suffix}-tests)
    add_executable(${tests} ${test_sources})
    target_include_directories(${tests} PRIVATE ${CMAKE_SOURCE_DIR}/tests/common)
    target_link_libraries(${tests} PRIVATE ${lab}_${side} wb_core Catch2::Catch2WithMain)
    catch_discover_tests(${tests}
      TEST_PREFIX "${side}/"
      EXTRA_ARGS -w NoTests
      TEST_LIST ${tests}_TESTS)
    # Labels and a time limit for every discovered test. A list passed through
    # catch_discover_tests' PROPERTIES is flattened ("LABELS forces solution"
    # sets one label), so they are set here, from the list Catch's generated
    # file defines; CTest reads this file after Catch's.
    set(labels_file ${CMAKE_CURRENT_BINARY_DIR}/${tests}_labels.cmake)
    file(WRITE ${labels_file}
      "foreach(t IN LISTS ${tests}_TESTS)\n"
      "  set_tests_properties(\"\${t}\" PROPERTIES LABELS \"${lab};${side}\" TIMEOUT 120)\n"
      "endforeach()\n")
    set_property(DIRECTORY APPEND PROPERTY TEST_INCLUDE_FILES ${labels_file})
  endif()
endfunction()

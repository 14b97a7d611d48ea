# swell_add_library(<name> SOURCES …): the static library swell_<name> with the alias and export
# name swell::<name>, its include/ directory public, installed and exported with swellTargets.
# One definition of what every swell library looks like, so they cannot drift apart.
function(swell_add_library name)
  cmake_parse_arguments(ARG "" "" "SOURCES" ${ARGN})
  add_library(swell_${name} ${ARG_SOURCES})
  add_library(swell::${name} ALIAS swell_${name})
  set_target_properties(swell_${name} PROPERTIES EXPORT_NAME ${name} POSITION_INDEPENDENT_CODE ON)
  target_include_directories(swell_${name} PUBLIC
    $<BUILD_INTERFACE:${CMAKE_CURRENT_SOURCE_DIR}/include>
    $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
  target_compile_features(swell_${name} PUBLIC cxx_std_20)
  install(TARGETS swell_${name} EXPORT swellTargets
          ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
          LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR})
  install(DIRECTORY include/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
endfunction()

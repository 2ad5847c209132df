# adb_layer(NAME source...): one layer of the plugin (core, bullet, io, scene), built as
# every layer is: the library adb_NAME with the alias adb::NAME, its public headers in the
# layer's include/ (internals in src/), position-independent (static libraries end up in
# shared ones), the project's warnings, and installed into the package's export set.
include_guard(GLOBAL)

function(adb_layer name)
  add_library(adb_${name} ${ARGN})
  add_library(adb::${name} ALIAS adb_${name})
  # No adb_NAME_EXPORTS define in a shared build (nothing reads it: the libraries export
  # every symbol): its objects are then compiled as the static build's are, and ccache
  # shares them (the package check's second build).
  set_target_properties(adb_${name} PROPERTIES EXPORT_NAME ${name} OUTPUT_NAME adb_${name}
    POSITION_INDEPENDENT_CODE ON DEFINE_SYMBOL "")
  target_include_directories(adb_${name}
    PUBLIC $<BUILD_INTERFACE:${CMAKE_CURRENT_SOURCE_DIR}/include>
           $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>
    PRIVATE ${CMAKE_CURRENT_SOURCE_DIR}/src)
  adb_set_warnings(adb_${name})
  install(TARGETS adb_${name} EXPORT adbTargets
    ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
    LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR})
  install(DIRECTORY include/adb DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
endfunction()

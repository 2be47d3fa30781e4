# build/prefix: the system MeshLab binaries with our plugins (scripts/make-prefix.sh).
get_property(_rk_plugins GLOBAL PROPERTY RELIEFKIT_PLUGINS)
set(RELIEFKIT_PREFIX ${CMAKE_BINARY_DIR}/prefix)
add_custom_target(prefix ALL
  COMMAND bash ${CMAKE_SOURCE_DIR}/scripts/make-prefix.sh ${RELIEFKIT_PREFIX} ${CMAKE_BINARY_DIR}/plugins ${MESHLAB_SYSTEM_DIR}
  DEPENDS ${_rk_plugins} base_library
  COMMENT "Private MeshLab prefix with the ReliefKit plugins: ${RELIEFKIT_PREFIX}")

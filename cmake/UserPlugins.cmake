# install-user-plugins: the plugins (and the base-model library beside them) copied into the
# current user's MeshLabExtraPlugins/<version> folder, where MeshLab (2022.02 and later) loads
# plugins without anything written into its own installation:
#   cmake --build build-2025 --target install-user-plugins
# The folder is the one MeshLab computes on Linux (QStandardPaths::AppDataLocation of the
# application "MeshLab_64bit_fp" of "VCG", then MeshLabExtraPlugins/<its version>), resolved when
# the target runs: $XDG_DATA_HOME (default ~/.local/share)/VCG/MeshLab_64bit_fp/MeshLabExtraPlugins/2025.07.
get_property(_rk_plugins GLOBAL PROPERTY RELIEFKIT_PLUGINS)
set(_rk_app_source "${MESHLAB_SOURCE_DIR}/src/common/mlapplication.cpp")
if(EXISTS "${_rk_app_source}")
  file(READ "${_rk_app_source}" _rk_app)
endif()
if(NOT RELIEFKIT_MESHLAB_API STREQUAL "2020" AND _rk_app MATCHES "MeshLabExtraPlugins")
  set(_rk_files)
  foreach(p ${_rk_plugins})
    list(APPEND _rk_files $<TARGET_FILE:${p}>)
  endforeach()
  add_custom_target(install-user-plugins
    COMMAND ${CMAKE_COMMAND} "-DFILES=${_rk_files}" -DBASES=${RELIEFKIT_BASES_DIR} -DVERSION=${RELIEFKIT_MESHLAB_VERSION}
      -P ${CMAKE_SOURCE_DIR}/cmake/InstallUserPlugins.cmake
    DEPENDS ${_rk_plugins} base_library
    COMMENT "ReliefKit's plugins into the user's MeshLabExtraPlugins/${RELIEFKIT_MESHLAB_VERSION}"
    VERBATIM)
else()
  add_custom_target(install-user-plugins
    COMMAND ${CMAKE_COMMAND} -E echo "MeshLab ${RELIEFKIT_MESHLAB_API} has no per-user plugin folder: cmake --install puts the plugins where it loads them"
    COMMAND ${CMAKE_COMMAND} -E false)
endif()

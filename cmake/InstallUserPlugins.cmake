# cmake -DFILES=a.so;b.so -DBASES=dir -DVERSION=2025.07 -P InstallUserPlugins.cmake (the target
# install-user-plugins of cmake/UserPlugins.cmake): copies them into the folder MeshLab <VERSION>
# loads a user's extra plugins from on Linux, and the base-model library beside them.
if(DEFINED ENV{XDG_DATA_HOME} AND NOT "$ENV{XDG_DATA_HOME}" STREQUAL "")
  set(data_home "$ENV{XDG_DATA_HOME}")
elseif(DEFINED ENV{HOME})
  set(data_home "$ENV{HOME}/.local/share")
else()
  message(FATAL_ERROR "neither XDG_DATA_HOME nor HOME is set: cannot find the user's MeshLab folder")
endif()
set(folder "${data_home}/VCG/MeshLab_64bit_fp/MeshLabExtraPlugins/${VERSION}")
file(MAKE_DIRECTORY "${folder}")
file(COPY ${FILES} DESTINATION "${folder}")
file(REMOVE_RECURSE "${folder}/reliefkit-bases")
file(COPY "${BASES}/" DESTINATION "${folder}/reliefkit-bases")
list(LENGTH FILES n)
message(STATUS "${n} ReliefKit plugins and the base-model library in ${folder}")

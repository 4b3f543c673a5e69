# Scene front ends and mesh readers (included by scene/CMakeLists.txt).
target_sources(deltapath_scene PRIVATE
  ${CMAKE_CURRENT_LIST_DIR}/loader.cpp
  ${CMAKE_CURRENT_LIST_DIR}/yaml_loader.cpp
  ${CMAKE_CURRENT_LIST_DIR}/yaml_values.cpp
  ${CMAKE_CURRENT_LIST_DIR}/yaml_materials.cpp
  ${CMAKE_CURRENT_LIST_DIR}/yaml_textures.cpp
  ${CMAKE_CURRENT_LIST_DIR}/yaml_media.cpp
  ${CMAKE_CURRENT_LIST_DIR}/yaml_shapes.cpp
  ${CMAKE_CURRENT_LIST_DIR}/yaml_transform.cpp
  ${CMAKE_CURRENT_LIST_DIR}/yaml_lights.cpp
  ${CMAKE_CURRENT_LIST_DIR}/mesh_io.cpp
  ${CMAKE_CURRENT_LIST_DIR}/mesh_obj.cpp
  ${CMAKE_CURRENT_LIST_DIR}/mesh_ply.cpp)
target_link_libraries(deltapath_scene PRIVATE yaml-cpp tinyobjloader::tinyobjloader)

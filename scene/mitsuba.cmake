# Mitsuba 0.5/0.6 and 3.x XML importer, its XML reader, spectra and .serialized meshes
# (included by scene/CMakeLists.txt).
target_sources(deltapath_scene PRIVATE
  ${CMAKE_CURRENT_LIST_DIR}/xml_reader.cpp
  ${CMAKE_CURRENT_LIST_DIR}/spectrum.cpp
  ${CMAKE_CURRENT_LIST_DIR}/mitsuba_serialized.cpp
  ${CMAKE_CURRENT_LIST_DIR}/mitsuba_object.cpp
  ${CMAKE_CURRENT_LIST_DIR}/mitsuba_loader.cpp
  ${CMAKE_CURRENT_LIST_DIR}/mitsuba_bsdfs.cpp
  ${CMAKE_CURRENT_LIST_DIR}/mitsuba_textures.cpp
  ${CMAKE_CURRENT_LIST_DIR}/mitsuba_shapes.cpp
  ${CMAKE_CURRENT_LIST_DIR}/mitsuba_media.cpp
  ${CMAKE_CURRENT_LIST_DIR}/mitsuba_emitters.cpp)
target_link_libraries(deltapath_scene PRIVATE ZLIB::ZLIB pugixml::pugixml)

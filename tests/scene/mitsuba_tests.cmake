# Mitsuba XML importer, XML reader, spectra and .serialized meshes (included by
# tests/scene/CMakeLists.txt).
dp_add_test(test_mitsuba
  SOURCES ${CMAKE_CURRENT_LIST_DIR}/test_mitsuba.cpp ${CMAKE_CURRENT_LIST_DIR}/test_mitsuba_scenes.cpp
  DEPS deltapath_scene deltapath_integrators ZLIB::ZLIB
  LABELS unit slow)

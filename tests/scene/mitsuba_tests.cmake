# Mitsuba XML importer, XML reader, spectra and .serialized meshes (included by
# tests/scene/CMakeLists.txt).
dp_add_test(test_mitsuba
  SOURCES ${CMAKE_CURRENT_LIST_DIR}/test_mitsuba.cpp
  DEPS deltapath_scene_loaders deltapath_integrators ZLIB::ZLIB
  LABELS unit)
# The public reference scenes (../shared/scenes, or $DP_SHARED_SCENES) in their own
# executable: when the folder is absent its first test case exits with 77 before any
# assertion, and ctest reports the tests as skipped, not passed (try:
# DP_SHARED_SCENES=/nonexistent ctest -R test_mitsuba_scenes).
dp_add_test(test_mitsuba_scenes
  SOURCES ${CMAKE_CURRENT_LIST_DIR}/test_mitsuba_scenes.cpp
  DEPS deltapath_scene_loaders deltapath_integrators Boost::boost
  LABELS unit slow)
set_tests_properties(test_mitsuba_scenes_unit test_mitsuba_scenes_slow PROPERTIES SKIP_RETURN_CODE 77)
# The strict XML reader under the importer (pugixml plus the checks it adds).
dp_add_test(test_xml_reader
  SOURCES ${CMAKE_CURRENT_LIST_DIR}/test_xml_reader.cpp
  DEPS deltapath_scene_loaders
  LABELS unit)

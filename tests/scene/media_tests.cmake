# Participating media (scene/media/phase_function.h, scene/media/free_flight.h,
# scene/media/medium_interface.h): HG and free-flight chi-square, weight unbiasedness (stat),
# normalisation and boundary bookkeeping (unit).
dp_add_test(test_media
  SOURCES ${CMAKE_CURRENT_LIST_DIR}/test_media.cpp
  DEPS deltapath_scene_loaders dp_test_support
  LABELS unit stat)

# Grid media (scene/media/density_grid.h, grid_tracking.h): .vol I/O and loader errors,
# trilinear lookup (unit); ratio and delta tracking against analytic transmittance and
# free-flight densities (stat).
dp_add_test(test_grid_media
  SOURCES ${CMAKE_CURRENT_LIST_DIR}/test_grid_media.cpp
  DEPS deltapath_scene_loaders dp_test_support
  LABELS unit stat)

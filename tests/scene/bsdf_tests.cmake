# BSDF, microfacet, Fresnel and texture tests (scene layer).
dp_add_test(test_bsdf
  SOURCES ${CMAKE_CURRENT_LIST_DIR}/test_bsdf_chi2.cpp
          ${CMAKE_CURRENT_LIST_DIR}/test_bsdf_consistency.cpp
          ${CMAKE_CURRENT_LIST_DIR}/test_bsdf_energy.cpp
          ${CMAKE_CURRENT_LIST_DIR}/test_fresnel_microfacet.cpp
          ${CMAKE_CURRENT_LIST_DIR}/test_texture.cpp
          ${CMAKE_CURRENT_LIST_DIR}/bsdf_test_cases.cpp
  DEPS deltapath_scene_loaders dp_test_support
  LABELS unit stat)

# Materials (BSDFs), microfacet and Fresnel helpers, textures.
target_sources(deltapath_scene PRIVATE
  ${CMAKE_CURRENT_LIST_DIR}/texture.cpp
  ${CMAKE_CURRENT_LIST_DIR}/fresnel.cpp
  ${CMAKE_CURRENT_LIST_DIR}/microfacet.cpp
  ${CMAKE_CURRENT_LIST_DIR}/rough_transmittance.cpp
  ${CMAKE_CURRENT_LIST_DIR}/bsdf_diffuse.cpp
  ${CMAKE_CURRENT_LIST_DIR}/bsdf_phong.cpp
  ${CMAKE_CURRENT_LIST_DIR}/bsdf_mirror.cpp
  ${CMAKE_CURRENT_LIST_DIR}/bsdf_dielectric.cpp
  ${CMAKE_CURRENT_LIST_DIR}/bsdf_rough_dielectric.cpp
  ${CMAKE_CURRENT_LIST_DIR}/bsdf_conductor.cpp
  ${CMAKE_CURRENT_LIST_DIR}/bsdf_plastic.cpp
  ${CMAKE_CURRENT_LIST_DIR}/bsdf_rough_plastic.cpp
  ${CMAKE_CURRENT_LIST_DIR}/bsdf_two_sided.cpp
  ${CMAKE_CURRENT_LIST_DIR}/bsdf_null_mask.cpp)
target_link_libraries(deltapath_scene PUBLIC Boost::boost)

# Shapes, emitters and the camera (included by scene/CMakeLists.txt).
target_sources(deltapath_scene PRIVATE
  ${CMAKE_CURRENT_LIST_DIR}/triangle_mesh.cpp
  ${CMAKE_CURRENT_LIST_DIR}/sphere.cpp
  ${CMAKE_CURRENT_LIST_DIR}/emitter_area.cpp
  ${CMAKE_CURRENT_LIST_DIR}/emitter_point.cpp
  ${CMAKE_CURRENT_LIST_DIR}/emitter_directional.cpp
  ${CMAKE_CURRENT_LIST_DIR}/emitter_environment.cpp
  ${CMAKE_CURRENT_LIST_DIR}/camera.cpp)
# Participating media: phase function, free-flight sampling and transmittance.
target_sources(deltapath_scene PRIVATE
  ${CMAKE_CURRENT_LIST_DIR}/phase_function.cpp
  ${CMAKE_CURRENT_LIST_DIR}/free_flight.cpp)

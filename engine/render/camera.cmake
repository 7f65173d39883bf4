# strata_camera: the contract's camera (Camera.cpp), pure math. Its own small
# library because both the GPU renderer (strata_render) and the CPU reference
# (strata_reference) sample exactly the same rays through it. Included by
# engine/render/CMakeLists.txt.
add_library(strata_camera STATIC
  ${CMAKE_CURRENT_LIST_DIR}/Camera.cpp
  ${CMAKE_CURRENT_LIST_DIR}/ViewBounds.cpp
)
target_include_directories(strata_camera PUBLIC ${STRATA_INCLUDE_DIR})
target_link_libraries(strata_camera PUBLIC strata_core glm::glm PRIVATE strata_warnings)
# Bounds come from geometry; ViewBounds walks the scene tree over the model.
target_link_libraries(strata_camera PUBLIC strata_geometry)

// One triangle that covers the whole viewport: vertices (-1,-1), (3,-1), (-1,3)
// in clip space, for gl_VertexID 0, 1, 2. Cheaper than a quad (no diagonal
// seam where fragments are shaded twice) and needs no vertex buffer:
// glDrawArrays(GL_TRIANGLES, 0, 3) with an empty vertex array bound.
vec2 fullscreenPosition(int vertexId) {
    return vec2(float((vertexId & 1) << 2) - 1.0, float((vertexId & 2) << 1) - 1.0);
}

// strata-bench's floor: every leaf's triangles drawn once, depth-tested, no CSG.
layout(location = 0) in vec3 position;   // world space

uniform mat4 viewProjection;

void main() {
    gl_Position = viewProjection * vec4(position, 1.0);
}

// strata-view's lines over the CSG image: the axes, their scale markers, the
// corner axis cross and the leaves' edges (apps/strata-view/Overlay.h).
layout(location = 0) in vec3 position;  // world space; the view's pixels for screen-space lines
layout(location = 1) in vec3 lineColor;
layout(location = 2) in float kind;     // the edge's leaf (>= 0), or kSolid / kDashed

uniform mat4 viewProjection;
uniform vec3 eye;
uniform vec3 forward;
uniform vec2 viewSize;
uniform bool screenSpace;

out float viewDepth;
out vec3 color;
flat out float lineKind;

void main() {
    color = lineColor;
    lineKind = kind;
    if (screenSpace) {
        gl_Position = vec4(position.xy / viewSize * 2.0 - 1.0, 0.0, 1.0);
        viewDepth = 0.0;
    } else {
        gl_Position = viewProjection * vec4(position, 1.0);
        // Affine in the position, so the perspective-correct interpolation is exact.
        viewDepth = dot(position - eye, forward);
    }
}

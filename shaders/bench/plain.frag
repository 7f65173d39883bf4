// strata-bench's floor: one constant colour; the cost is rasterization and the depth test.
layout(location = 0) out vec4 color;

void main() {
    color = vec4(0.8, 0.8, 0.8, 1.0);
}

// Auto peeling's question before each further pass of one operand: does any
// pixel hold more surfaces than the passes so far have peeled? The peel pass
// counted every pixel's surfaces into the stencil during its first pass; a
// fullscreen triangle drawn with the stencil test "count > 2 * passes" inside
// an occlusion query answers, at the cost of a rectangle of stencil reads
// instead of one more geometry pass over the operand. No colour is written.
layout(early_fragment_tests) in;

void main() {}

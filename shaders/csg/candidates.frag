// Marks candidate pixels for the evaluator: drawn for each operand the result
// can show (one that is not complemented in the tree, TreeProgram.h), with
// colour writes off and the stencil set to 1 (FrameTargets::kCandidate). The
// result lies inside the union of those operands, so elsewhere it has no
// surface and the evaluator need not run.
void main() {}

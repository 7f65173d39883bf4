// strata_gl_tests gets its test sources from tests/<layer>/CMakeLists.txt;
// this file gives the target a source of its own so it configures even in a
// checkout whose GPU tests are all switched off.

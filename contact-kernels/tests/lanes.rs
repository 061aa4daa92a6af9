//! The lane value types' arithmetic, lane by lane the scalar operation's
//! bits: the tests beside the code in src/lanes.rs, which depends on `std`
//! alone and is compiled here on its own (the library has no unit-test
//! target, so its generated kernels compile once).

#[path = "../src/lanes.rs"]
#[allow(dead_code, unused_imports)]
mod lanes;

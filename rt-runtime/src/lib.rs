//! rt-runtime: the host side (issue #3).

#!/bin/sh
# RUSTC_WORKSPACE_WRAPPER for `npm test`: compiles this crate with clippy-driver, which lints as
# `cargo clippy` does and then builds as rustc does, so one build both lints and tests each target
# (a separate `cargo clippy` pass would check every dependency a second time). Warnings are errors.
exec clippy-driver "$@" -D warnings

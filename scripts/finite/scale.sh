#!/bin/sh
# Finite sheets at the issue's large sizes (issue 42, item 10): rotating squares one DOF at
# 20×20 and 40×40, IH15's 20×20 completion without pruning (the ignored test), then the
# figures per size (example finite_scaling). Optimised test profile; minutes on two cores.
set -e
cd "$(dirname "$0")/../.."
cargo test -p isogami --test it large_sheets_keep -- --ignored
cargo run -p isogami --example finite_scaling -- "$@"

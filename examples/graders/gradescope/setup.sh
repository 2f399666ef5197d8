#!/usr/bin/env bash
# Gradescope runs this once, when it builds the autograder's image (Ubuntu,
# as root, from the folder this zip was unpacked in: /autograder/source).
# The zip holds this file, run_autograder and a copy of the rasterlab
# repository in rasterlab/.
set -euo pipefail
apt-get update -qq
apt-get install -y -qq build-essential curl python3 nodejs
curl --proto '=https' --tlsv1.2 -sSf https://sh.rustup.rs | sh -s -- -y --profile minimal
. "$HOME/.cargo/env"
cargo install --locked --path /autograder/source/rasterlab --root /usr/local
rasterlab --version

#!/usr/bin/env bash
# Source this file: bundled_openacc_dir NAME prints the folder of the OpenACC runs shipped in
# data/openacc/NAME.tar.xz (JRC OpenACC, CC BY 4.0: see data/openacc/README.md), unpacked once
# into build/data/openacc/NAME with CMake's own archive support (no xz tool needed), and again
# whenever the archive changes.
bundled_openacc_dir() {
  local name=$1
  local repo
  repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
  local archive=$repo/data/openacc/$name.tar.xz
  local destination=$repo/build/data/openacc/$name
  [ -r "$archive" ] || { echo "bundled_openacc_dir: no archive $archive" >&2; return 1; }
  local hash
  hash=$(sha256sum "$archive" | cut -d' ' -f1)
  if [ "$(cat "$destination/.unpacked_from_archive" 2>/dev/null)" != "$hash" ]; then
    rm -rf "$destination"
    mkdir -p "$destination"
    (cd "$destination" && cmake -E tar xf "$archive") || return 1
    echo -n "$hash" > "$destination/.unpacked_from_archive"
  fi
  echo "$destination"
}

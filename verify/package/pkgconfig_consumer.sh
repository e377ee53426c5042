#!/bin/sh
# pkgconfig_consumer.sh PREFIX MAIN_CPP WORK_DIR CXX: builds the consumer with
# the flags of the installed gearimpact.pc alone, and runs it.
set -eu
prefix=$1 main=$2 work=$3 cxx=$4
rm -rf "$work" && mkdir -p "$work"
PKG_CONFIG_PATH="$prefix/lib/pkgconfig"
export PKG_CONFIG_PATH
flags=$(pkg-config --cflags --libs gearimpact)
echo "pkg-config --cflags --libs gearimpact: $flags"
# shellcheck disable=SC2086 # the flags are words
"$cxx" -std=c++17 "$main" $flags -o "$work/consumer"
"$work/consumer"

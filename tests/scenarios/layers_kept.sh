#!/bin/sh
# The modules of src/ keep to the layers of doc/architecture.md: no module uses
# a module of a folder on a row above its own or beside it (tools/layer_check.py
# holds the rows of the drawing).
# usage: layers_kept.sh FLEXMECH COMPARE_TABLES WORKDIR
set -u
python3 tools/layer_check.py src

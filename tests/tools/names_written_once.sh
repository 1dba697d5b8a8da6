#!/usr/bin/env bash
# Fails when a plugin writes a parameter or port name outside its config/port structs' visit:
# string reads such as ctx.param<T>("x"), ctx.input<T>("x"), is_wired("x"), param_error("x", ...)
# or string declarations such as s.add_double("x"), s.input<T>("x", ...).
# (tools/count_plugin_boilerplate.py reports the same counts in detail.)
set -u
plugins=${1:?usage: names_written_once.sh PLUGINS_DIR}
pattern='\badd_(bool|int|double|string|list|string_list)\( *"|\b(param|input|output)<[^>]*>\( *"|\bis_wired\( *"|\bparam_error\( *"|\boutput_path_param\( *"'
if grep -rnE --include='*.cpp' --include='*.hpp' "$pattern" "$plugins"; then
  echo "names_written_once: the lines above name a parameter or port outside a visit" >&2
  exit 1
fi
echo "names_written_once: no parameter or port name outside the visits under $plugins"

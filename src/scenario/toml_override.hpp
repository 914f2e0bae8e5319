#pragma once
// Setting a key of a parsed input file from outside it (`--set KEY=VALUE`, sweeps).
#include <string>
#include <toml++/toml.h>

namespace j232::scenario {

// Writes `value` at the dotted `key` of the document, creating tables on the way. A
// key that passes through an array of tables ([[housing.guards]]) is set in every
// element; NAME[N] (counted from 1) picks the Nth ("field.objects[2].per_area"). A value
// that reads as a TOML number, boolean or array is stored as one, anything else as a
// string ("1000 rpm"). Throws InputError naming `origin`.
void set_key(toml::table& document, const std::string& key, const std::string& value, const std::string& origin);

// "KEY=VALUE" form of set_key.
void assign(toml::table& document, const std::string& assignment, const std::string& origin = "--set");

}  // namespace j232::scenario

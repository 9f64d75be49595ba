// JsonOutput: how the CLI lays out the JSON documents it writes (--stats): nlohmann's values,
// one top-level member per line, nested values on that line, so a person can read them and
// `grep` finds a key with its value.
#ifndef accelvolume_cli_JsonOutput_h
#define accelvolume_cli_JsonOutput_h

#include <nlohmann/json.hpp>

#include <ostream>

namespace accelvolume::cli
{

// Members keep the order they were added in.
using JsonDocument = nlohmann::ordered_json;

// Non-finite numbers become null (JSON has no NaN or infinity).
JsonDocument JsonNumber(double value);

void WriteJsonDocument(std::ostream& stream, const JsonDocument& document);

} // namespace accelvolume::cli

#endif

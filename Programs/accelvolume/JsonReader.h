// JsonReader: a small JSON parser for the CLI's transfer-function files (no third-party library).
#ifndef accelvolume_cli_JsonReader_h
#define accelvolume_cli_JsonReader_h

#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace accelvolume::cli
{

// One parsed JSON value. Objects keep their keys sorted (std::map) and reject duplicates, since a
// repeated key in a transfer-function file is almost certainly a mistake.
struct JsonValue
{
  enum class Kind
  {
    Null,
    Bool,
    Number,
    String,
    Array,
    Object
  };
  Kind kind = Kind::Null;
  bool boolean = false;
  double number = 0;
  std::string text;
  std::vector<JsonValue> items;
  std::map<std::string, JsonValue> members;
  int line = 1, column = 1; // where the value starts, for error messages

  // "line L, column C"
  std::string Where() const;
};

// Thrown with a one-line message "line L, column C: what went wrong".
class JsonError : public std::runtime_error
{
public:
  using std::runtime_error::runtime_error;
};

// Parses a complete document (one value, surrounding white space only). Accepts RFC 8259 JSON;
// \u escapes are decoded to UTF-8 (surrogate pairs included).
JsonValue ParseJson(const std::string& text);

const char* JsonKindName(JsonValue::Kind kind);

} // namespace accelvolume::cli

#endif

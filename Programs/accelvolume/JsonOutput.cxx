#include "JsonOutput.h"

#include <cmath>
#include <string>

namespace accelvolume::cli
{
namespace
{

// Invalid UTF-8 (a file name, say) is replaced rather than thrown on.
std::string Dump(const JsonDocument& value)
{
  return value.dump(-1, ' ', false, JsonDocument::error_handler_t::replace);
}

// A value on one line, with ", " and ": " separators; scalars and escaping are the library's.
void WriteInline(std::ostream& stream, const JsonDocument& value)
{
  if (value.is_object())
  {
    stream << "{";
    const char* separator = "";
    for (const auto& member : value.items())
    {
      stream << separator << Dump(JsonDocument(member.key())) << ": ";
      WriteInline(stream, member.value());
      separator = ", ";
    }
    stream << "}";
  }
  else if (value.is_array())
  {
    stream << "[";
    const char* separator = "";
    for (const JsonDocument& item : value)
    {
      stream << separator;
      WriteInline(stream, item);
      separator = ", ";
    }
    stream << "]";
  }
  else
  {
    stream << Dump(value);
  }
}

} // namespace

JsonDocument JsonNumber(double value)
{
  return std::isfinite(value) ? JsonDocument(value) : JsonDocument(nullptr);
}

void WriteJsonDocument(std::ostream& stream, const JsonDocument& document)
{
  if (!document.is_object())
  {
    WriteInline(stream, document);
    stream << "\n";
    return;
  }
  stream << "{\n";
  std::size_t remaining = document.size();
  for (const auto& member : document.items())
  {
    stream << "  " << Dump(JsonDocument(member.key())) << ": ";
    WriteInline(stream, member.value());
    stream << (--remaining ? ",\n" : "\n");
  }
  stream << "}\n";
}

} // namespace accelvolume::cli

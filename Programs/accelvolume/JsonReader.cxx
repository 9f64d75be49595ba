// JsonReader: a recursive-descent JSON parser that reports line and column of the first error.
#include "JsonReader.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>

namespace accelvolume::cli
{
namespace
{

// Deep nesting is never meaningful in a transfer-function file; the limit keeps a hostile file
// from exhausting the stack.
constexpr int MaxDepth = 64;

class Parser
{
public:
  explicit Parser(const std::string& text)
    : Text(text)
  {
  }

  JsonValue Document()
  {
    this->SkipSpace();
    JsonValue value = this->Value(0);
    this->SkipSpace();
    if (this->Position < this->Text.size())
    {
      this->Fail("unexpected '" + this->Describe() + "' after the end of the document");
    }
    return value;
  }

private:
  const std::string& Text;
  std::size_t Position = 0;
  int Line = 1, Column = 1;

  [[noreturn]] void Fail(const std::string& message) const
  {
    throw JsonError("line " + std::to_string(this->Line) + ", column " +
      std::to_string(this->Column) + ": " + message);
  }

  std::string Describe() const
  {
    if (this->Position >= this->Text.size())
    {
      return "end of file";
    }
    const unsigned char c = static_cast<unsigned char>(this->Text[this->Position]);
    return c >= 0x20 && c < 0x7f ? std::string(1, static_cast<char>(c))
                                 : "byte " + std::to_string(c);
  }

  char Peek() const
  {
    return this->Position < this->Text.size() ? this->Text[this->Position] : '\0';
  }

  void Advance()
  {
    if (this->Text[this->Position++] == '\n')
    {
      ++this->Line;
      this->Column = 1;
    }
    else
    {
      ++this->Column;
    }
  }

  void SkipSpace()
  {
    while (this->Position < this->Text.size())
    {
      const char c = this->Text[this->Position];
      if (c != ' ' && c != '\t' && c != '\n' && c != '\r')
      {
        return;
      }
      this->Advance();
    }
  }

  void Expect(char wanted, const char* context)
  {
    if (this->Peek() != wanted || this->Position >= this->Text.size())
    {
      this->Fail(
        std::string("expected '") + wanted + "' " + context + ", got '" + this->Describe() + "'");
    }
    this->Advance();
  }

  JsonValue Value(int depth)
  {
    if (depth > MaxDepth)
    {
      this->Fail("nesting deeper than " + std::to_string(MaxDepth) + " levels");
    }
    JsonValue value;
    value.line = this->Line;
    value.column = this->Column;
    const char c = this->Peek();
    if (this->Position >= this->Text.size())
    {
      this->Fail("expected a value, got end of file");
    }
    if (c == '{')
    {
      this->Object(value, depth);
    }
    else if (c == '[')
    {
      this->Array(value, depth);
    }
    else if (c == '"')
    {
      value.kind = JsonValue::Kind::String;
      value.text = this->String();
    }
    else if (c == '-' || (c >= '0' && c <= '9'))
    {
      value.kind = JsonValue::Kind::Number;
      value.number = this->Number();
    }
    else if (this->Literal("true") || this->Literal("false"))
    {
      value.kind = JsonValue::Kind::Bool;
      value.boolean = c == 't';
    }
    else if (this->Literal("null"))
    {
      value.kind = JsonValue::Kind::Null;
    }
    else
    {
      this->Fail("expected a value, got '" + this->Describe() + "'");
    }
    return value;
  }

  bool Literal(const std::string& word)
  {
    if (this->Text.compare(this->Position, word.size(), word) != 0)
    {
      return false;
    }
    for (std::size_t i = 0; i < word.size(); ++i)
    {
      this->Advance();
    }
    return true;
  }

  void Object(JsonValue& value, int depth)
  {
    value.kind = JsonValue::Kind::Object;
    this->Advance(); // '{'
    this->SkipSpace();
    if (this->Peek() == '}')
    {
      this->Advance();
      return;
    }
    while (true)
    {
      this->SkipSpace();
      if (this->Peek() != '"')
      {
        this->Fail("expected a quoted key, got '" + this->Describe() + "'");
      }
      const int line = this->Line, column = this->Column;
      const std::string key = this->String();
      this->SkipSpace();
      this->Expect(':', "after an object key");
      this->SkipSpace();
      JsonValue member = this->Value(depth + 1);
      if (!value.members.emplace(key, std::move(member)).second)
      {
        throw JsonError("line " + std::to_string(line) + ", column " + std::to_string(column) +
          ": duplicate key '" + key + "'");
      }
      this->SkipSpace();
      if (this->Peek() == ',')
      {
        this->Advance();
        continue;
      }
      this->Expect('}', "or ',' in an object");
      return;
    }
  }

  void Array(JsonValue& value, int depth)
  {
    value.kind = JsonValue::Kind::Array;
    this->Advance(); // '['
    this->SkipSpace();
    if (this->Peek() == ']')
    {
      this->Advance();
      return;
    }
    while (true)
    {
      this->SkipSpace();
      value.items.push_back(this->Value(depth + 1));
      this->SkipSpace();
      if (this->Peek() == ',')
      {
        this->Advance();
        continue;
      }
      this->Expect(']', "or ',' in an array");
      return;
    }
  }

  double Number()
  {
    // Check the JSON grammar first (strtod alone would accept "0x1p3", "inf", "1." and so on).
    const std::size_t start = this->Position;
    auto digits = [&]()
    {
      bool any = false;
      while (this->Peek() >= '0' && this->Peek() <= '9' && this->Position < this->Text.size())
      {
        this->Advance();
        any = true;
      }
      return any;
    };
    if (this->Peek() == '-')
    {
      this->Advance();
    }
    const bool leadingZero = this->Peek() == '0';
    if (!digits())
    {
      this->Fail("malformed number");
    }
    if (leadingZero && this->Position - start > (this->Text[start] == '-' ? 2u : 1u))
    {
      this->Fail("malformed number (leading zero)");
    }
    if (this->Peek() == '.')
    {
      this->Advance();
      if (!digits())
      {
        this->Fail("malformed number (digits expected after '.')");
      }
    }
    if (this->Peek() == 'e' || this->Peek() == 'E')
    {
      this->Advance();
      if (this->Peek() == '+' || this->Peek() == '-')
      {
        this->Advance();
      }
      if (!digits())
      {
        this->Fail("malformed number (digits expected in the exponent)");
      }
    }
    const std::string text = this->Text.substr(start, this->Position - start);
    errno = 0;
    const double number = std::strtod(text.c_str(), nullptr);
    if (errno == ERANGE && !std::isfinite(number))
    {
      this->Fail("number '" + text + "' is out of range");
    }
    return number;
  }

  unsigned Hex4()
  {
    unsigned code = 0;
    for (int i = 0; i < 4; ++i)
    {
      const char c = this->Peek();
      const int digit = c >= '0' && c <= '9' ? c - '0'
        : c >= 'a' && c <= 'f'               ? c - 'a' + 10
        : c >= 'A' && c <= 'F'               ? c - 'A' + 10
                                             : -1;
      if (digit < 0 || this->Position >= this->Text.size())
      {
        this->Fail("malformed \\u escape");
      }
      code = code * 16 + static_cast<unsigned>(digit);
      this->Advance();
    }
    return code;
  }

  static void AppendUtf8(std::string& out, unsigned code)
  {
    if (code < 0x80)
    {
      out += static_cast<char>(code);
    }
    else if (code < 0x800)
    {
      out += static_cast<char>(0xc0 | (code >> 6));
      out += static_cast<char>(0x80 | (code & 0x3f));
    }
    else if (code < 0x10000)
    {
      out += static_cast<char>(0xe0 | (code >> 12));
      out += static_cast<char>(0x80 | ((code >> 6) & 0x3f));
      out += static_cast<char>(0x80 | (code & 0x3f));
    }
    else
    {
      out += static_cast<char>(0xf0 | (code >> 18));
      out += static_cast<char>(0x80 | ((code >> 12) & 0x3f));
      out += static_cast<char>(0x80 | ((code >> 6) & 0x3f));
      out += static_cast<char>(0x80 | (code & 0x3f));
    }
  }

  std::string String()
  {
    this->Advance(); // opening quote
    std::string out;
    while (true)
    {
      if (this->Position >= this->Text.size())
      {
        this->Fail("unterminated string");
      }
      const char c = this->Peek();
      if (c == '"')
      {
        this->Advance();
        return out;
      }
      if (static_cast<unsigned char>(c) < 0x20)
      {
        this->Fail("control character in a string (a missing closing quote?)");
      }
      this->Advance();
      if (c != '\\')
      {
        out += c;
        continue;
      }
      const char escape = this->Peek();
      if (this->Position >= this->Text.size())
      {
        this->Fail("unterminated string");
      }
      this->Advance();
      switch (escape)
      {
        case '"':
        case '\\':
        case '/':
          out += escape;
          break;
        case 'b':
          out += '\b';
          break;
        case 'f':
          out += '\f';
          break;
        case 'n':
          out += '\n';
          break;
        case 'r':
          out += '\r';
          break;
        case 't':
          out += '\t';
          break;
        case 'u':
        {
          unsigned code = this->Hex4();
          if (code >= 0xd800 && code < 0xdc00 && this->Text.compare(this->Position, 2, "\\u") == 0)
          {
            this->Advance();
            this->Advance();
            const unsigned low = this->Hex4();
            code = low >= 0xdc00 && low < 0xe000
              ? 0x10000 + ((code - 0xd800) << 10) + (low - 0xdc00)
              : 0xfffd;
          }
          AppendUtf8(out, code >= 0xd800 && code < 0xe000 ? 0xfffd : code);
          break;
        }
        default:
          this->Fail(std::string("invalid escape '\\") + escape + "' in a string");
      }
    }
  }
};

} // namespace

std::string JsonValue::Where() const
{
  return "line " + std::to_string(this->line) + ", column " + std::to_string(this->column);
}

JsonValue ParseJson(const std::string& text)
{
  return Parser(text).Document();
}

const char* JsonKindName(JsonValue::Kind kind)
{
  switch (kind)
  {
    case JsonValue::Kind::Null:
      return "null";
    case JsonValue::Kind::Bool:
      return "a boolean";
    case JsonValue::Kind::Number:
      return "a number";
    case JsonValue::Kind::String:
      return "a string";
    case JsonValue::Kind::Array:
      return "an array";
    case JsonValue::Kind::Object:
      return "an object";
  }
  return "unknown";
}

} // namespace accelvolume::cli

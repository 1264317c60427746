// Finds the function bodies of a C++ source file and their lengths in lines, for the check that
// no function in src/ runs past a reader's page (tools/function_lengths.cpp, make test).
// A lexer, not a parser: comments, string and character literals (raw strings too) and
// preprocessor lines are blanked first; then braces are followed with a stack of scopes.
// A brace at namespace or class level opens a function when the declaration before it has a
// parameter list outside any initializer (`= ...`); braces inside a body belong to it, so a
// lambda counts toward the function that holds it. Constructor initializer lists (`: a{x}, b(y)`)
// are part of their function's header.
#pragma once

#include <cctype>
#include <string>
#include <string_view>
#include <vector>

namespace vdc::tools {

struct FunctionSpan {
  std::string name;   // the declarator before the parameter list: `Scene::load`, `operator==`
  int first_line = 0; // the declaration's first line (1-based)
  int last_line = 0;  // the line of the closing brace
  int lines() const { return last_line - first_line + 1; }
};

// `source` with comments, literals and preprocessor lines replaced by spaces, newlines kept, so
// that every brace left is code and every offset keeps its line.
inline std::string blank_non_code(std::string_view source) {
  std::string out(source);
  const std::size_t n = out.size();
  auto blank = [&](std::size_t from, std::size_t to) {
    for (std::size_t k = from; k < to && k < n; ++k)
      if (out[k] != '\n') out[k] = ' ';
  };
  bool line_start = true;
  std::size_t i = 0;
  while (i < n) {
    const char c = out[i];
    if (line_start && c == '#') {  // a directive, with its continuation lines
      std::size_t j = i;
      while (j < n && !(out[j] == '\n' && (j == 0 || out[j - 1] != '\\'))) ++j;
      blank(i, j);
      i = j;
      continue;
    }
    if (c == '\n') {
      line_start = true;
      ++i;
      continue;
    }
    if (c != ' ' && c != '\t') line_start = false;
    if (c == '/' && i + 1 < n && out[i + 1] == '/') {
      std::size_t j = i;
      while (j < n && out[j] != '\n') ++j;
      blank(i, j);
      i = j;
    } else if (c == '/' && i + 1 < n && out[i + 1] == '*') {
      const std::size_t end = out.find("*/", i + 2);
      const std::size_t j = end == std::string::npos ? n : end + 2;
      blank(i, j);
      i = j;
    } else if (c == 'R' && i + 1 < n && out[i + 1] == '"' &&
               (i == 0 || !(std::isalnum(static_cast<unsigned char>(out[i - 1])) || out[i - 1] == '_'))) {
      const std::size_t open = out.find('(', i + 2);
      if (open == std::string::npos) {
        ++i;
        continue;
      }
      const std::string closing = ")" + out.substr(i + 2, open - i - 2) + "\"";
      const std::size_t end = out.find(closing, open);
      const std::size_t j = end == std::string::npos ? n : end + closing.size();
      blank(i, j);
      i = j;
    } else if (c == '"' || (c == '\'' && !(i > 0 && std::isxdigit(static_cast<unsigned char>(out[i - 1]))))) {
      // A quote after a hex digit is a digit separator (1'000), not a character literal.
      std::size_t j = i + 1;
      while (j < n && out[j] != c && out[j] != '\n') j += out[j] == '\\' ? 2 : 1;
      blank(i, j + 1);
      i = j + 1;
    } else {
      ++i;
    }
  }
  return out;
}

namespace detail {

inline bool is_word_char(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; }

inline std::vector<std::string> words_of(std::string_view text) {
  std::vector<std::string> words;
  std::size_t i = 0;
  while (i < text.size()) {
    if (is_word_char(text[i])) {
      std::size_t j = i;
      while (j < text.size() && is_word_char(text[j])) ++j;
      words.emplace_back(text.substr(i, j - i));
      i = j;
    } else {
      ++i;
    }
  }
  return words;
}

// The offset of the first '(' outside template brackets, or npos when an initializer's `=`
// comes first (or there is no '(' at all). `operator` takes the symbol after it as its name.
inline std::size_t parameter_list_start(std::string_view header) {
  int angle = 0;
  for (std::size_t i = 0; i < header.size(); ++i) {
    const char c = header[i];
    if (is_word_char(c)) {
      std::size_t j = i;
      while (j < header.size() && is_word_char(header[j])) ++j;
      if (header.substr(i, j - i) == "operator") {
        std::size_t k = j;
        while (k < header.size() && header[k] == ' ') ++k;
        if (k + 1 < header.size() && header[k] == '(' && header[k + 1] == ')') k += 2;  // operator()
        while (k < header.size() && header[k] != '(') ++k;
        return k < header.size() ? k : std::string_view::npos;
      }
      i = j - 1;
    } else if (c == '<') {
      ++angle;
    } else if (c == '>' && angle > 0) {
      --angle;
    } else if (c == '=' && angle == 0) {
      return std::string_view::npos;
    } else if (c == '(' && angle == 0) {
      return i;
    }
  }
  return std::string_view::npos;
}

// The offset just past the ')' that closes the '(' at `open`.
inline std::size_t matching_paren_end(std::string_view text, std::size_t open) {
  int depth = 0;
  for (std::size_t i = open; i < text.size(); ++i) {
    if (text[i] == '(') ++depth;
    if (text[i] == ')' && --depth == 0) return i + 1;
  }
  return text.size();
}

// Whether a single ':' (not '::') stands in `text` outside parentheses: a constructor's
// initializer list after its parameters.
inline bool has_initializer_colon(std::string_view text) {
  int depth = 0;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (c == '(') ++depth;
    if (c == ')') --depth;
    if (c == ':' && depth == 0) {
      const bool doubled = (i + 1 < text.size() && text[i + 1] == ':') || (i > 0 && text[i - 1] == ':');
      if (!doubled) return true;
    }
  }
  return false;
}

inline std::string declarator_name(std::string_view header, std::size_t paren) {
  std::size_t end = paren;
  while (end > 0 && header[end - 1] == ' ') --end;
  std::size_t begin = end;
  while (begin > 0 && (is_word_char(header[begin - 1]) || header[begin - 1] == ':' || header[begin - 1] == '~' ||
                       std::string_view("=!<>+-*/%&|^[]").find(header[begin - 1]) != std::string_view::npos))
    --begin;
  std::string name(header.substr(begin, end - begin));
  return name.empty() ? std::string("(unnamed)") : name;
}

}  // namespace detail

// Every function body at namespace or class level in `source`, in the order they open.
inline std::vector<FunctionSpan> find_functions(std::string_view source) {
  using namespace detail;
  const std::string code = blank_non_code(source);
  enum class Scope { container, function, other };
  std::vector<Scope> stack;
  std::vector<FunctionSpan> found;
  std::string header;        // the declaration read so far at the current container level
  int header_line = 0;       // the line of its first character
  int line = 1;
  int function_depth = -1;   // the stack size at which the open function's body began
  FunctionSpan open_function;
  auto at_container_level = [&] {
    for (Scope s : stack)
      if (s != Scope::container) return false;
    return true;
  };
  auto reset_header = [&] {
    header.clear();
    header_line = 0;
  };
  for (std::size_t i = 0; i < code.size(); ++i) {
    const char c = code[i];
    if (c == '\n') {
      ++line;
      if (!header.empty()) header += ' ';
      continue;
    }
    const bool container_level = at_container_level();
    if (c == '{') {
      if (!container_level) {
        stack.push_back(Scope::other);
        continue;
      }
      const std::vector<std::string> words = words_of(header);
      const std::size_t paren = parameter_list_start(header);
      bool is_container = false;
      for (const std::string& word : words)
        if (word == "namespace" || word == "extern") is_container = paren == std::string::npos || word == "extern";
      if (paren == std::string::npos) {
        for (const std::string& word : words)
          if (word == "class" || word == "struct" || word == "union" || word == "enum") is_container = true;
      }
      if (is_container) {
        stack.push_back(Scope::container);
        reset_header();
      } else if (paren != std::string::npos) {
        const std::size_t after = matching_paren_end(header, paren);
        std::size_t last = header.size();
        while (last > 0 && header[last - 1] == ' ') --last;
        const bool init_brace = has_initializer_colon(std::string_view(header).substr(after)) && last > 0 &&
                                (is_word_char(header[last - 1]) || header[last - 1] == '>');
        if (init_brace) {  // `: member{value}` in a constructor's initializer list
          stack.push_back(Scope::other);
          header += '{';
          continue;
        }
        open_function = FunctionSpan{declarator_name(header, paren), header_line ? header_line : line, 0};
        stack.push_back(Scope::function);
        function_depth = static_cast<int>(stack.size());
        reset_header();
      } else {
        stack.push_back(Scope::other);  // an aggregate initializer at namespace or class level
        header += '{';
      }
      continue;
    }
    if (c == '}') {
      if (stack.empty()) continue;
      const Scope closing = stack.back();
      const bool closes_function = closing == Scope::function && static_cast<int>(stack.size()) == function_depth;
      stack.pop_back();
      if (closes_function) {
        open_function.last_line = line;
        found.push_back(open_function);
        function_depth = -1;
        reset_header();
      } else if (closing == Scope::container) {
        reset_header();
      } else if (at_container_level()) {
        header += '}';  // the end of an initializer brace: the declaration goes on
      }
      continue;
    }
    if (!container_level) continue;
    if (c == ';') {
      reset_header();
      continue;
    }
    if (c == ':' && !(i + 1 < code.size() && code[i + 1] == ':') && !(i > 0 && code[i - 1] == ':')) {
      const std::vector<std::string> words = words_of(header);
      if (words.size() == 1 && (words[0] == "public" || words[0] == "private" || words[0] == "protected")) {
        reset_header();
        continue;
      }
    }
    if (c == ' ' || c == '\t' || c == '\r') {
      if (!header.empty()) header += ' ';
      continue;
    }
    if (header.empty()) header_line = line;
    header += c;
  }
  return found;
}

}  // namespace vdc::tools

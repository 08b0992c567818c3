#pragma once
/// \file
/// The typed exceptions of plmap. Every error names what it is about (file and line, element,
/// node) so that the command line can print one clear sentence.

#include <stdexcept>
#include <string>

namespace plmap {

/// Base of every error plmap raises on bad input or misuse.
class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// A file could not be read or parsed. The message names the file and, where it applies, the
/// line (text formats) or byte offset / element (binary formats).
class ParseError : public Error {
 public:
  ParseError(std::string file, std::string location, const std::string& what)
      : Error(file + (location.empty() ? "" : ":" + location) + ": " + what),
        file_(std::move(file)),
        location_(std::move(location)) {}
  const std::string& file() const { return file_; }
  const std::string& location() const { return location_; }

 private:
  std::string file_;
  std::string location_;
};

/// A surface violates what plmap requires (non-finite coordinates, index out of range,
/// degenerate or repeated elements). The message names the element or vertex.
class InvalidSurfaceError : public Error {
 public:
  using Error::Error;
};

/// The map builder was asked for something inconsistent (a node on the wrong element, an edge
/// whose endpoints share no element, crossing graph edges, ...).
class BuilderError : public Error {
 public:
  using Error::Error;
};

/// A stored map is inconsistent with its surfaces or with itself.
class InvalidMapError : public Error {
 public:
  using Error::Error;
};

}  // namespace plmap

#include "tests/fuzz/nff_mutator.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <sstream>
#include <vector>

namespace raycube::fuzz {
namespace {

std::vector<std::string> linesOf(std::string_view text) {
  std::vector<std::string> lines;
  std::string line;
  std::istringstream in{std::string(text)};
  while (std::getline(in, line)) lines.push_back(line);
  return lines;
}

std::string joined(const std::vector<std::string>& lines) {
  std::string text;
  for (const std::string& line : lines) text += line + "\n";
  return text;
}

std::vector<std::string> tokensOf(const std::string& line) {
  std::vector<std::string> tokens;
  std::istringstream in(line);
  for (std::string token; in >> token;) tokens.push_back(token);
  return tokens;
}

std::string lineOf(const std::vector<std::string>& tokens) {
  std::string line;
  for (const std::string& token : tokens) line += (line.empty() ? "" : " ") + token;
  return line;
}

bool isNumber(const std::string& token, double& value) {
  char* end = nullptr;
  value = std::strtod(token.c_str(), &end);
  return !token.empty() && end == token.c_str() + token.size();
}

std::size_t pick(std::size_t n, std::mt19937_64& random) {
  return std::uniform_int_distribution<std::size_t>(0, n - 1)(random);
}

// A number toward 0, +-huge, a denormal, float's edges, or a nudge of a few ulps to a few percent.
std::string perturbed(double value, std::mt19937_64& random) {
  static const std::array<const char*, 14> kSpecial = {"0",   "-0",       "1e300",  "-1e300", "3.4e38",
                                                       "6e7", "60617284", "1e-310", "1e-45",  "1e-30",
                                                       "65",  "1.7e216",  "-1",     "0.5"};
  switch (pick(4, random)) {
    case 0:
      return kSpecial[pick(kSpecial.size(), random)];
    case 1:
      return fmt::format("{}", value * (1 + std::ldexp(1.0, -int(10 + pick(42, random)))));
    case 2:
      return fmt::format("{}", value * std::ldexp(1.0, int(pick(60, random)) - 30));
    default:
      return fmt::format("{}", -value);
  }
}

// The index of a line starting with keyword k, or lines.size().
std::size_t lineStarting(const std::vector<std::string>& lines, std::string_view k, std::mt19937_64& random) {
  std::vector<std::size_t> found;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const std::vector<std::string> tokens = tokensOf(lines[i]);
    if (!tokens.empty() && tokens[0] == k) found.push_back(i);
  }
  return found.empty() ? lines.size() : found[pick(found.size(), random)];
}

// The lines an object takes: its own, and a polygon's or patch's vertex lines.
std::size_t linesOfObjectAt(const std::vector<std::string>& lines, std::size_t i) {
  const std::vector<std::string> tokens = tokensOf(lines[i]);
  double n = 0;
  if (tokens.size() >= 2 && (tokens[0] == "p" || tokens[0] == "pp") && isNumber(tokens[1], n) && n >= 0 &&
      n < 64)
    return std::min<std::size_t>(1 + std::size_t(n), lines.size() - i);
  if (!tokens.empty() && tokens[0] == "c") return std::min<std::size_t>(3, lines.size() - i);
  return 1;
}

void perturbANumber(std::vector<std::string>& lines, std::mt19937_64& random) {
  for (int attempt = 0; attempt < 8; ++attempt) {
    std::string& line = lines[pick(lines.size(), random)];
    std::vector<std::string> tokens = tokensOf(line);
    std::vector<std::size_t> numbers;
    double value;
    for (std::size_t k = 0; k < tokens.size(); ++k)
      if (isNumber(tokens[k], value)) numbers.push_back(k);
    if (numbers.empty()) continue;
    const std::size_t k = numbers[pick(numbers.size(), random)];
    isNumber(tokens[k], value);
    tokens[k] = perturbed(value, random);
    line = lineOf(tokens);
    return;
  }
}

// A polygon's vertex leaves the plane of the others: by a rounding error, or by a lot.
void liftAVertex(std::vector<std::string>& lines, std::mt19937_64& random) {
  const std::size_t p = lineStarting(lines, pick(2, random) == 0 ? "p" : "pp", random);
  if (p == lines.size()) return;
  const std::size_t span = linesOfObjectAt(lines, p);
  if (span < 2) return;
  std::string& vertex = lines[p + 1 + pick(span - 1, random)];
  std::vector<std::string> tokens = tokensOf(vertex);
  if (tokens.size() < 3) return;
  const std::size_t k = pick(3, random);
  double value;
  if (!isNumber(tokens[k], value)) return;
  static const std::array<double, 6> kLift = {1e-12, 1e-7, 1e-3, 0.1, 1, 5};
  tokens[k] = fmt::format("{}", value + kLift[pick(kLift.size(), random)] * (pick(2, random) ? 1 : -1));
  vertex = lineOf(tokens);
}

// An object twice (coplanar overlapping faces, equal distances to tie), sometimes its polygon's vertices
// turned round by one so that the copy's fan and plane are computed from other corners.
void duplicateAnObject(std::vector<std::string>& lines, std::mt19937_64& random) {
  static const std::array<const char*, 5> kObjects = {"p", "pp", "s", "c", "f"};
  const std::string_view keyword = kObjects[pick(kObjects.size(), random)];
  const std::size_t i = lineStarting(lines, keyword, random);
  if (i == lines.size()) return;
  const std::size_t span = linesOfObjectAt(lines, i);
  std::vector<std::string> copy(lines.begin() + std::ptrdiff_t(i), lines.begin() + std::ptrdiff_t(i + span));
  if (copy.size() > 3 && pick(2, random) == 0) std::rotate(copy.begin() + 1, copy.begin() + 2, copy.end());
  lines.insert(lines.begin() + std::ptrdiff_t(i + span), copy.begin(), copy.end());
}

}  // namespace

std::string mutateNff(std::string_view text, std::mt19937_64& random) {
  std::vector<std::string> lines = linesOf(text);
  if (lines.empty()) return std::string(text);
  switch (pick(6, random)) {
    case 0:
    case 1:
      perturbANumber(lines, random);
      break;
    case 2:
      liftAVertex(lines, random);
      break;
    case 3:
      duplicateAnObject(lines, random);
      break;
    case 4:
      lines.erase(lines.begin() + std::ptrdiff_t(pick(lines.size(), random)));
      break;
    default:
      std::swap(lines[pick(lines.size(), random)], lines[pick(lines.size(), random)]);
      break;
  }
  return joined(lines);
}

}  // namespace raycube::fuzz

// A file's text rewritten node by node in pieces formatted side by side: how the text formats
// write a variant of a large file on every thread (the same bytes for any number of threads).
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace mlsformats
{
/// The text with the old text of each of nodes (in file order, node i's starting at begin(i))
/// replaced by what write(out, i) appends to out (returning where node i's old text ends), as 64
/// pieces formatted side by side, to be written one after the other (AtomicWrite::add).
template <class Begin, class Write>
std::vector<std::string> rewriteInPieces(const std::string& text, std::size_t nodes, Begin begin, Write write)
{
  constexpr long Pieces = 64;
  std::vector<std::string> pieces(Pieces);
  // piece p: from its first node's text (the file's start for p = 0) to the next piece's
  auto start = [&](long p) {
    const std::size_t first = nodes * p / Pieces;
    return p == 0 ? std::size_t(0) : p == Pieces ? text.size() : first < nodes ? static_cast<std::size_t>(begin(first)) : text.size();
  };
#pragma omp parallel for schedule(dynamic)
  for (long p = 0; p < Pieces; ++p)
  {
    std::string& out = pieces[p];
    std::size_t copied = start(p);
    const std::size_t end = start(p + 1);
    out.reserve((end - copied) * 9 / 8);
    for (std::size_t i = nodes * p / Pieces; i < nodes * (p + 1) / Pieces; ++i)
    {
      const std::size_t at = static_cast<std::size_t>(begin(i));
      out.append(text, copied, at - copied);
      copied = write(out, i);
    }
    out.append(text, copied, end - copied);
  }
  return pieces;
}
} // namespace mlsformats

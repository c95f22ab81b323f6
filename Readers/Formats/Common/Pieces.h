// A source file written with its nodes' text rewritten: the span that holds the nodes read into
// memory and formatted in pieces side by side, each written as soon as those before it are (so one
// piece is written while the next is formatted), the bytes before and after it read and written on
// in chunks. How the text formats write a variant of a large file on every thread (the same bytes
// for any number of threads).
#pragma once

#include "Common/TextFile.h"

#include <cstddef>
#include <exception>
#include <string>
#include <string_view>

namespace mlsformats
{
/// Appends to out the bytes of source with the old text of each of nodes (in file order, node i's
/// starting at begin(i), the last's ending by end) replaced by what
/// write(piece, text, at, i) appends to piece: text is the nodes' span, node i's text starts at
/// text[at], and write returns where in text it ends. The nodes are formatted in 64 pieces, each
/// appended to out as soon as those before it are. What write throws is thrown once all are done
/// (and source's hash is checked: a changed source is said as such).
template <class Begin, class Write>
void rewriteInPieces(AtomicWrite::Aside& out, SourceBytes& source, std::size_t nodes, std::size_t end, Begin begin, Write write)
{
  if (nodes == 0)
  {
    out.copy(source, 0, source.size());
    return;
  }
  const std::size_t base = static_cast<std::size_t>(begin(0));
  out.copy(source, 0, base);
  const std::string_view text = source.read(base, end);
  constexpr long Pieces = 64;
  std::size_t last = 0;          // where the last node's text ends in text
  std::exception_ptr failure;    // the first piece's that failed
#pragma omp parallel
  {
    std::string piece; // this thread's, reused piece after piece
    // piece p: its nodes' text and what follows up to the next piece's first node (the last
    // piece: up to the end of the last node's text)
#pragma omp for ordered schedule(dynamic, 1)
    for (long p = 0; p < Pieces; ++p)
    {
      const std::size_t first = nodes * p / Pieces, after = nodes * (p + 1) / Pieces;
      piece.clear();
      if (first < after)
      {
        std::size_t copied = static_cast<std::size_t>(begin(first)) - base;
        piece.reserve((static_cast<std::size_t>(begin(after - 1)) - base - copied) * 9 / 8 + 256);
        try
        {
          for (std::size_t i = first; i < after; ++i)
          {
            const std::size_t at = static_cast<std::size_t>(begin(i)) - base;
            piece.append(text, copied, at - copied);
            copied = write(piece, text, at, i);
          }
        }
        catch (...)
        {
#pragma omp critical(rewriteInPiecesFailure)
          failure = failure ? failure : std::current_exception();
          copied = text.size();
        }
        if (after < nodes)
        {
          const std::size_t next = static_cast<std::size_t>(begin(after)) - base;
          piece.append(text, copied, next - copied);
        }
        else
        {
          last = copied;
        }
      }
#pragma omp ordered
      out.append(piece);
    }
  }
  out.append(text.substr(last));
  out.copy(source, end, source.size()); // its last bytes passed, the source's hash is checked
  if (failure)
  {
    std::rethrow_exception(failure);
  }
}
} // namespace mlsformats

#include <tissuefem/base/parallel.h>

#include <ostream>
#include <streambuf>

namespace tissuefem::parallel_tools
{
  namespace
  {
    /// A stream buffer that swallows every character.
    class NullBuffer : public std::streambuf
    {
    protected:
      int
      overflow(int c) override
      {
        return traits_type::not_eof(c);
      }
    };
  } // namespace


  std::ostream &
  screen()
  {
    static NullBuffer   buffer;
    static std::ostream discard(&buffer);
    return is_root() ? std::cout : discard;
  }
} // namespace tissuefem::parallel_tools

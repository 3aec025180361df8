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


  std::string
  first_error(const std::string &local_error)
  {
    for (const std::string &e :
         Utilities::MPI::all_gather(communicator(), local_error))
      if (!e.empty())
        return e;
    return {};
  }
} // namespace tissuefem::parallel_tools

#pragma once

#include <iostream>
#include <sstream>
#include <string>

namespace tissuefem
{
  /**
   * Keeps what libraries write to std::cerr while it lives (deal.II's
   * muparser wrapper, Amesos: multi-line reports of errors that
   * tissuefem reports itself, on one line naming the parameter or the
   * solver's code). std::cerr is restored on destruction, also when an
   * exception leaves the scope.
   */
  class CerrCapture
  {
  public:
    CerrCapture()
        : previous(std::cerr.rdbuf(captured.rdbuf()))
    {
    }

    ~CerrCapture()
    {
      std::cerr.rdbuf(previous);
    }

    CerrCapture(const CerrCapture &) = delete;
    CerrCapture &
    operator=(const CerrCapture &)
      = delete;

    /// What was written so far.
    std::string
    text() const
    {
      return captured.str();
    }

  private:
    std::ostringstream captured;
    std::streambuf    *previous;
  };
} // namespace tissuefem

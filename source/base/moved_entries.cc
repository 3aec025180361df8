#include <tissuefem/base/input_error.h>
#include <tissuefem/base/moved_entries.h>
#include <tissuefem/base/parallel.h>
#include <tissuefem/base/parameter_tools.h>

#include <iostream>
#include <map>
#include <set>

namespace tissuefem::moved_entries
{
  namespace
  {
    struct Move
    {
      std::string new_path, default_value;
    };

    /// Old path -> where it went (declared for dim = 1, 2 and 3 alike).
    std::map<std::string, Move> &
    moves()
    {
      static std::map<std::string, Move> table;
      return table;
    }

    /// Runs @p f(name) with @p prm inside the subsections of @p path.
    template <typename F>
    auto
    at(ParameterHandler &prm, const std::string &path, const F &f)
    {
      const std::vector<std::string> pieces = split_and_trim(path, '/');
      for (unsigned int i = 0; i + 1 < pieces.size(); ++i)
        prm.enter_subsection(pieces[i]);
      struct Leave
      {
        ParameterHandler &prm;
        std::size_t       depth;
        ~Leave()
        {
          for (std::size_t i = 0; i < depth; ++i)
            prm.leave_subsection();
        }
      } leave{prm, pieces.size() - 1};
      return f(pieces.back());
    }
  } // namespace


  void
  declare(ParameterHandler            &prm,
          const std::string           &old_path,
          const std::string           &new_path,
          const std::string           &default_value,
          const Patterns::PatternBase &pattern,
          const std::string           &documentation)
  {
    Assert(old_path != new_path,
           ExcMessage("A moved entry needs two different places"));
    at(prm, new_path, [&](const std::string &name) {
      prm.declare_entry(name, default_value, pattern, documentation);
    });
    at(prm, old_path, [&](const std::string &name) {
      prm.declare_entry(name,
                        default_value,
                        pattern,
                        "Moved to '" + new_path
                          + "'; still read here, with a notice.");
    });
    moves()[old_path] = {new_path, default_value};
  }


  void
  set(ParameterHandler &prm, const std::string &path, const std::string &value)
  {
    std::string key;
    for (const std::string &piece : split_and_trim(path, '/'))
      key += (key.empty() ? "" : "/") + piece;
    std::string target = key;
    for (const auto &[old_path, move] : moves())
      if (key == old_path || key == move.new_path)
        {
          target = move.new_path;
          at(prm, old_path, [&](const std::string &name) {
            prm.set(name, move.default_value);
          });
        }
    at(prm, target, [&](const std::string &name) { prm.set(name, value); });
  }


  void
  apply(ParameterHandler &prm)
  {
    static std::set<std::string> noticed;
    for (const auto &[old_path, move] : moves())
      {
        const std::string old_value
          = at(prm, old_path, [&](auto &name) { return prm.get(name); });
        if (old_value == move.default_value)
          continue;
        const std::string new_value
          = at(prm, move.new_path, [&](auto &name) { return prm.get(name); });
        require(new_value == move.default_value || new_value == old_value,
                old_path,
                "was moved to '" + move.new_path
                  + "', which the file sets to another value; set only '"
                  + move.new_path + "'");
        at(prm, move.new_path, [&](const std::string &name) {
          prm.set(name, old_value);
        });
        if (noticed.insert(old_path).second && parallel_tools::is_root())
          std::cerr << "tissuefem: notice: '" << old_path << "' is now '"
                    << move.new_path << "'; the old name is still read."
                    << std::endl;
      }
  }
} // namespace tissuefem::moved_entries

#include <deal.II/base/mpi.h>

#include <tissuefem/base/input_error.h>
#include <tissuefem/output/checkpoint.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <sstream>

namespace tissuefem::output
{
  namespace
  {
    // 2: postprocessors' state as 'state' lines.
    const std::string format = "tissuefem-checkpoint 2";

    std::string
    vector_file(const std::string &directory, const unsigned int rank)
    {
      return directory + "/vectors." + std::to_string(rank) + ".bin";
    }

    double
    parse_double(const std::string &text)
    {
      return exact_value(text);
    }

    /// A postprocessor's name as one word, and back.
    std::string
    state_key(std::string name)
    {
      std::replace(name.begin(), name.end(), ' ', '_');
      return name;
    }

    std::string
    state_name(std::string key)
    {
      std::replace(key.begin(), key.end(), '_', ' ');
      return key;
    }
  } // namespace


  std::string
  exact_text(const double value)
  {
    std::ostringstream s;
    s << std::hexfloat << value;
    return s.str();
  }


  double
  exact_value(const std::string &text)
  {
    // std::hexfloat input is unreliable across standard libraries.
    return std::strtod(text.c_str(), nullptr);
  }


  void
  write_checkpoint(const std::string                     &directory,
                   const Checkpoint                      &checkpoint,
                   const std::vector<const VectorType *> &vectors)
  {
    namespace fs            = std::filesystem;
    const MPI_Comm    comm  = parallel_tools::communicator();
    const unsigned    rank  = Utilities::MPI::this_mpi_process(comm);
    const std::string fresh = directory + ".new", old = directory + ".old";
    std::string       error;
    if (rank == 0)
      {
        std::error_code code;
        fs::remove_all(fresh, code);
        fs::create_directories(fresh, code);
        if (code)
          error = "cannot create '" + fresh + "': " + code.message();
      }
    error = Utilities::MPI::broadcast(comm, error);
    if (!error.empty())
      throw SolverError("checkpoint: " + error);

    {
      std::ofstream       out(vector_file(fresh, rank), std::ios::binary);
      const std::uint64_t n = vectors.size();
      out.write(reinterpret_cast<const char *>(&n), sizeof(n));
      for (const VectorType *v : vectors)
        {
          const std::uint64_t size = v->locally_owned_size();
          out.write(reinterpret_cast<const char *>(&size), sizeof(size));
          out.write(reinterpret_cast<const char *>(v->trilinos_vector()[0]),
                    size * sizeof(double));
        }
      out.close();
      if (!out)
        error = "cannot write " + vector_file(fresh, rank);
    }
    error = Utilities::MPI::max(error.empty() ? 0 : 1, comm)
              ? "cannot write the vectors into '" + fresh + "'"
              : "";
    if (!error.empty())
      throw SolverError("checkpoint: " + error);

    if (rank == 0)
      {
        {
          std::ofstream out(fresh + "/checkpoint.txt");
          out << std::hexfloat;
          out << format << '\n'
              << "step " << checkpoint.step << '\n'
              << "time " << checkpoint.time << '\n'
              << "processes " << checkpoint.n_processes << '\n'
              << "unknowns " << checkpoint.n_dofs << '\n'
              << (checkpoint.distributed_mesh ? "mesh distributed\n" : "")
              << "integrator " << checkpoint.integrator << '\n';
          for (const double s : checkpoint.integrator_scalars)
            out << "scalar " << s << '\n';
          for (const auto &[file, size] : checkpoint.file_sizes)
            out << "file " << size << ' ' << file << '\n';
          // Names may hold spaces, the lines anything but line breaks.
          for (const auto &[name, lines] : checkpoint.postprocessor_state)
            for (const std::string &l : lines)
              out << "state " << state_key(name) << ' ' << l << '\n';
          out << "end\n";
          out.close();
          if (!out)
            error = "cannot write '" + fresh + "/checkpoint.txt'";
        }
        // Swap in the new directory; a crash leaves either the old
        // checkpoint, or the new one as '.new' beside it.
        std::error_code code;
        if (error.empty())
          {
            fs::remove_all(old, code);
            if (fs::exists(directory, code))
              fs::rename(directory, old, code);
            if (!code)
              fs::rename(fresh, directory, code);
            if (code)
              error = "cannot move '" + fresh + "' to '" + directory
                      + "': " + code.message();
            fs::remove_all(old, code);
          }
      }
    error = Utilities::MPI::broadcast(comm, error);
    if (!error.empty())
      throw SolverError("checkpoint: " + error);
  }


  Checkpoint
  read_checkpoint(const std::string               &directory,
                  const std::vector<VectorType *> &vectors)
  {
    const MPI_Comm    comm  = parallel_tools::communicator();
    const unsigned    rank  = Utilities::MPI::this_mpi_process(comm);
    const std::string where = "--restart '" + directory + "': ";
    Checkpoint        checkpoint;
    std::ifstream     in(directory + "/checkpoint.txt");
    if (!in)
      throw InputError(where
                       + "no checkpoint.txt (not a checkpoint "
                         "directory, or an incomplete one)");
    std::string line;
    std::getline(in, line);
    if (line != format)
      throw InputError(where + "checkpoint.txt does not start with '" + format
                       + "'");
    bool ended = false;
    while (std::getline(in, line))
      try
        {
          std::istringstream fields(line);
          std::string        key, value;
          fields >> key;
          if (key == "end")
            {
              ended = true;
              break;
            }
          fields >> value;
          if (key == "step")
            checkpoint.step = std::stoul(value);
          else if (key == "time")
            checkpoint.time = parse_double(value);
          else if (key == "processes")
            checkpoint.n_processes = std::stoul(value);
          else if (key == "unknowns")
            checkpoint.n_dofs = std::stoull(value);
          else if (key == "mesh" && value == "distributed")
            checkpoint.distributed_mesh = true;
          else if (key == "integrator")
            {
              std::string rest;
              std::getline(fields, rest);
              checkpoint.integrator = value + rest;
            }
          else if (key == "scalar")
            checkpoint.integrator_scalars.push_back(parse_double(value));
          else if (key == "file" || key == "state")
            {
              std::string rest;
              std::getline(fields >> std::ws, rest);
              if (key == "file")
                checkpoint.file_sizes[rest] = std::stoull(value);
              else
                checkpoint.postprocessor_state[state_name(value)].push_back(
                  rest);
            }
          else
            throw InputError(where + "unknown entry '" + key
                             + "' in checkpoint.txt");
        }
      catch (const std::logic_error &)
        {
          // std::stoul and friends on a corrupt entry.
          throw InputError(where + "unreadable line '" + line
                           + "' in checkpoint.txt");
        }
    if (!ended)
      throw InputError(where + "checkpoint.txt is truncated");
    if (checkpoint.n_processes != Utilities::MPI::n_mpi_processes(comm))
      throw InputError(where + "written by "
                       + std::to_string(checkpoint.n_processes)
                       + " processes; restart with as many");

    std::string   error;
    std::ifstream data(vector_file(directory, rank), std::ios::binary);
    std::uint64_t n = 0;
    data.read(reinterpret_cast<char *>(&n), sizeof(n));
    if (!data || n != vectors.size())
      error = "holds other vectors than this scene's integrator keeps";
    for (unsigned int k = 0; k < vectors.size() && error.empty(); ++k)
      {
        std::uint64_t size = 0;
        data.read(reinterpret_cast<char *>(&size), sizeof(size));
        if (!data || size != vectors[k]->locally_owned_size())
          {
            error = "vector sizes differ from this scene's (another mesh or "
                    "element?)";
            break;
          }
        data.read(reinterpret_cast<char *>(vectors[k]->trilinos_vector()[0]),
                  size * sizeof(double));
        if (!data)
          error = "vectors file is truncated";
      }
    if (Utilities::MPI::max(error.empty() ? 0 : 1, comm))
      throw InputError(
        where
        + (error.empty() ? "another process's vectors do not fit" : error));
    return checkpoint;
  }
} // namespace tissuefem::output

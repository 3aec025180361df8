#include <tissuefem/output/obstacle_view.h>
#include <tissuefem/output/view_server.h>
#include <tissuefem/output/wire_format.h>
#include <tissuefem/tool/contact_tool.h>

#include <cstdint>

namespace tissuefem::output
{
  template <int dim>
  ObstacleView<dim>::ObstacleView(const contact::PenaltyContact<dim> *contact,
                                  const tool::ContactTool<dim>       *tool)
      : contact(contact)
      , tool(tool)
  {
  }


  template <int dim>
  std::string
  ObstacleView<dim>::json() const
  {
    std::string result = "[";
    if (contact)
      for (unsigned int i = 0; i < contact->obstacles().size(); ++i)
        {
          const bool is_tool = tool && tool->obstacle() == i;
          result += std::string(i == 0 ? "" : ",") + "{\"name\":"
                    + json_quote(contact->obstacles()[i].name) + ",\"role\":\""
                    + (!is_tool                ? "obstacle"
                       : tool->follows_mouse() ? "mouse"
                                               : "tool")
                    + "\"}";
        }
    return result + "]";
  }


  template <int dim>
  void
  ObstacleView<dim>::append_drawings(std::string      &bytes,
                                     const Point<dim> &centre,
                                     const double      extent) const
  {
    const unsigned int n = contact ? contact->obstacles().size() : 0;
    put<std::uint32_t>(bytes, n);
    for (unsigned int i = 0; i < n; ++i)
      {
        const auto drawing = contact->obstacles()[i].drawing(centre, extent);
        put<std::uint32_t>(bytes, drawing.vertices.size());
        put<std::uint32_t>(bytes, drawing.triangles.size() / 3);
        std::vector<float> corners(3 * drawing.vertices.size(), 0.f);
        for (unsigned int v = 0; v < drawing.vertices.size(); ++v)
          for (unsigned int d = 0; d < dim; ++d)
            corners[3 * v + d] = drawing.vertices[v][d];
        put_all(bytes, corners);
        std::vector<std::uint32_t> triangles(drawing.triangles.begin(),
                                             drawing.triangles.end());
        put_all(bytes, triangles);
      }
  }


  template <int dim>
  Tensor<1, dim>
  ObstacleView<dim>::placement(const contact::Pose<dim> &pose)
  {
    return pose.translation + pose.pivot
           - pose.rotation * Tensor<1, dim>(pose.pivot);
  }


  template <int dim>
  void
  ObstacleView<dim>::append_poses(std::string                 &bytes,
                                  const contact::Reports<dim> &reports,
                                  const double                 time) const
  {
    if (!contact)
      return;
    const auto &obstacles = contact->obstacles();
    for (unsigned int i = 0; i < obstacles.size(); ++i)
      {
        const auto           pose = obstacles[i].pose(time);
        std::vector<float>   block(floats_per_obstacle, 0.f);
        const Tensor<1, dim> offset = placement(pose);
        for (unsigned int d = 0; d < 3; ++d)
          block[3 + 4 * d] = 1;
        for (unsigned int d = 0; d < dim; ++d)
          {
            block[d] = offset[d];
            for (unsigned int e = 0; e < dim; ++e)
              block[3 + 3 * d + e] = pose.rotation[d][e];
            if (i < reports.size())
              block[12 + d] = -reports[i].force[d];
            if (tool && tool->obstacle() == i)
              block[16 + d] = tool->mouse_offset(time)[d];
          }
        block[15] = i < reports.size() && reports[i].area > 0 ? 1 : 0;
        put_all(bytes, block);
      }
  }

  template class ObstacleView<1>;
  template class ObstacleView<2>;
  template class ObstacleView<3>;
} // namespace tissuefem::output

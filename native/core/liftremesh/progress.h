// Progress reporting from the core to its callers (CLI, Python module, FreeCAD task panel).
#pragma once

#include <functional>
#include <string>

namespace liftremesh {

struct Progress {
    std::string stage;          //!< "normals", "optimize", "rdt", "repair", "quality", ...
    int iteration = 0;          //!< current iteration within the stage (0 when not iterative)
    int total = 0;              //!< iterations planned for the stage (0 when not iterative)
    double energy = 0.0;        //!< objective value (optimize stage), else 0
    double gradient_norm = 0.0; //!< |dF/dV| (optimize stage), else 0
};

//! Called from the calling thread between steps; return false to stop: the core then throws
//! Cancelled and returns nothing half-made.
using ProgressCallback = std::function<bool(const Progress&)>;

} // namespace liftremesh

// Command-line options of the liftremesh tool.
#pragma once

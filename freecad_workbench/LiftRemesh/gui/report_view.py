"""The quality report of a remesh as the task panel shows it: a table (input vs output) and a
histogram of the triangle quality kappa (the report's 10 bins over [0, 0.1), ..., [0.9, 1])."""
from PySide import QtCore, QtGui

INPUT_COLOR = "#a8a8a8"
OUTPUT_COLOR = "#2f6fba"

# (label, key in report["input"] / report["output"], format)
ROWS = (
    ("vertices", "vertices", "{:d}"),
    ("triangles", "triangles", "{:d}"),
    ("κ min", "kappa_min", "{:.3f}"),
    ("κ mean", "kappa_mean", "{:.3f}"),
    ("min. angle", "min_angle_deg", "{:.1f}°"),
    ("boundary edges", "boundary_edges", "{:d}"),
    ("boundary loops", "boundary_loops", "{:d}"),
    ("Euler char. χ", "euler_characteristic", "{:d}"),
    ("self-intersections", "self_intersections", "{:d}"),
)


def _cell(fmt, value):
    """One table cell; '–' when the report lacks the value."""
    if value is None:
        return "–"
    try:
        return fmt.format(value)
    except (ValueError, TypeError):
        return str(value)


def report_html(report):
    """The report as a small HTML table (input vs output) plus the distance to the source."""
    source, output = report.get("input", {}), report.get("output", {})
    lines = ['<table cellspacing="0" cellpadding="2">',
             '<tr><th></th><th align="right">input</th><th align="right">&nbsp;output</th></tr>']
    for label, key, fmt in ROWS:
        lines.append('<tr><td>%s</td><td align="right">%s</td><td align="right"><b>%s</b></td></tr>'
                     % (label, _cell(fmt, source.get(key)), _cell(fmt, output.get(key))))
    lines.append("</table>")
    lines.append(distance_line(report))
    extra = []
    repaired = [(report.get("input_duplicates_removed"), "repeated"), (report.get("input_degenerate_removed"), "degenerate")]
    extra += ["%d %s facet(s) of the source dropped" % (n, why) for n, why in repaired if n]
    if report.get("input_facets_turned"):
        extra.append("%d facet(s) of the source turned" % report["input_facets_turned"])
    if report.get("holes_filled"):
        extra.append("%d hole(s) filled" % report["holes_filled"])
    # counted by the core (report.h), as its warnings count them
    if report.get("cracks_closed"):
        extra.append("%d crack(s) of the source closed" % report["cracks_closed"])
    if report.get("vertex_fans_split"):
        extra.append("%d fan(s) of the source's non-manifold vertices split" % report["vertex_fans_split"])
    if (report.get("parts") or 1) > 1:
        extra.append("%d parts remeshed one by one" % report["parts"])
    seconds = sum((report.get("timings") or {}).values())
    if seconds:
        extra.append("remeshed in %.1f s" % seconds)
    if extra:
        lines.append("<br>" + ", ".join(extra))
    from .. import meshing

    for warning in meshing.report_warnings(report):
        lines.append('<br><span style="color:#b00000">Warning: %s.</span>' % warning)
    return "".join(lines)


def distance_line(report):
    """'Hausdorff distance: 0.12 % of the diagonal (0.05 mm)' or '' when it is missing."""
    relative = report.get("hausdorff_relative")
    if relative is None:
        return ""
    text = "Hausdorff distance to the source: <b>%.3g %%</b> of the bounding-box diagonal" % (100.0 * relative)
    diagonal = report.get("bbox_diagonal")
    if diagonal:
        text += " (%.3g mm)" % (relative * diagonal)
    return text


def summary(label, report):
    """One line for the console: the main figures of a report."""
    output = report.get("output", {})
    return ("%s: %s vertices, %s triangles, kappa min %.3f mean %.3f, min angle %.1f deg, "
            "Hausdorff %.3g %% of the diagonal"
            % (label, output.get("vertices"), output.get("triangles"), output.get("kappa_min", 0.0),
               output.get("kappa_mean", 0.0), output.get("min_angle_deg", 0.0),
               100.0 * (report.get("hausdorff_relative") or 0.0)))


def shares(counts):
    """Counts as fractions of their sum (all zero when the sum is)."""
    counts = list(counts or [])
    total = float(sum(counts))
    return [c / total if total else 0.0 for c in counts]


class KappaHistogram(QtGui.QWidget):
    """Bars of the share of triangles per kappa bin: input (grey) beside output (blue)."""

    def __init__(self, parent=None):
        super(KappaHistogram, self).__init__(parent)
        self.input_counts = []
        self.output_counts = []
        self.setMinimumHeight(120)
        self.setSizePolicy(QtGui.QSizePolicy.Expanding, QtGui.QSizePolicy.Fixed)

    def set_report(self, report):
        """Shows the histograms of a report (its input and output kappa_histogram)."""
        self.input_counts = list(report.get("input", {}).get("kappa_histogram") or [])
        self.output_counts = list(report.get("output", {}).get("kappa_histogram") or [])
        self.setToolTip(self.tooltip())
        self.update()

    def tooltip(self):
        """The exact counts per bin, as a tooltip."""
        rows = ["κ bin: input → output"]
        for i, out in enumerate(self.output_counts):
            before = self.input_counts[i] if i < len(self.input_counts) else 0
            rows.append("[%.1f, %.1f%s: %d → %d" % (i / 10.0, (i + 1) / 10.0, "]" if i == 9 else ")", before, out))
        return "\n".join(rows)

    def sizeHint(self):
        return QtCore.QSize(300, 130)

    def paintEvent(self, event):
        painter = QtGui.QPainter(self)
        try:
            painter.setRenderHint(QtGui.QPainter.Antialiasing, False)
            self._paint(painter)
        finally:
            painter.end()

    def _paint(self, painter):
        """Axes, legend and bars; bars are scaled to the largest share, non-zero ones stay visible."""
        text = self.palette().color(QtGui.QPalette.WindowText)
        metrics = painter.fontMetrics()
        line = metrics.height()
        left, right, top, bottom = 4, self.width() - 4, line + 4, self.height() - line - 2
        self._legend(painter, left, line, text)
        bins = max(len(self.output_counts), len(self.input_counts), 10)
        series = [(shares(self.input_counts), QtGui.QColor(INPUT_COLOR)),
                  (shares(self.output_counts), QtGui.QColor(OUTPUT_COLOR))]
        peak = max([max(s) if s else 0.0 for s, _ in series] + [1e-9])
        width = (right - left) / float(bins)
        for i in range(bins):
            for j, (values, color) in enumerate(series):
                value = values[i] if i < len(values) else 0.0
                if value <= 0.0:
                    continue
                height = max(2.0, (bottom - top) * value / peak)
                x = left + i * width + 1 + j * (width - 2) / 2.0
                painter.fillRect(QtCore.QRectF(x, bottom - height, (width - 2) / 2.0, height), color)
        painter.setPen(text)
        painter.drawLine(left, bottom, right, bottom)
        for value in (0.0, 0.5, 1.0):
            label = "%g" % value
            x = left + value * (right - left) - value * metrics.boundingRect(label).width()
            painter.drawText(int(x), bottom + line, label)

    def _legend(self, painter, left, line, text):
        """Two coloured squares with 'input' and 'output'."""
        x = left
        for name, color in (("input", INPUT_COLOR), ("output", OUTPUT_COLOR)):
            painter.fillRect(QtCore.QRectF(x, line / 4.0, line / 2.0, line / 2.0), QtGui.QColor(color))
            painter.setPen(text)
            painter.drawText(int(x + line * 0.75), int(line * 0.75), name)
            x += line + painter.fontMetrics().boundingRect(name).width() + line

"""Report stage: designer-facing output of analysed designs and design-to-targets runs:
plots and the summary table (:mod:`.design`), the self-contained HTML page and its Markdown
twin (:mod:`.html`), which answers go on which page (:mod:`.pages`) and the field picture of
a solved state (:mod:`.fields`)."""

from .design import (
                     arc_stress_plot,
                     comparison_plot,
                     default_design_report,
                     fatigue_rows,
                     markdown_summary,
                     summary_rows,
                     torque_plot,
                     write_analysis,
)
from .fields import field_picture
from .html import Figure, Page, Table, Text, folder_page, render_html, render_md, write_page
from .pages import (
                     compare_rows,
                     compensation_page,
                     design_page,
                     design_verdicts,
                     optimization_page,
                     param_table,
                     tolerance_page,
)
from .runs import (
                     compensation_json,
                     compensation_report,
                     design_report,
                     optimization_report,
                     slip_heat_files,
                     tolerance_report,
)

__all__ = ["compensation_json", "compensation_report", "design_report", "optimization_report", "slip_heat_files", "tolerance_report", "Figure", "Page", "Table", "Text", "arc_stress_plot", "compare_rows", "comparison_plot",
           "compensation_page", "default_design_report", "design_page", "design_verdicts", "fatigue_rows", "field_picture",
           "folder_page", "markdown_summary", "optimization_page", "param_table", "render_html", "render_md",
           "summary_rows", "tolerance_page", "torque_plot", "write_analysis", "write_page"]

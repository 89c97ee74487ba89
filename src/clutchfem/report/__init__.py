"""Report stage: designer-facing output of analysed designs and design-to-targets runs:
plots (:mod:`.design`), the summary table (:mod:`.answer_rows`), the self-contained HTML page and its Markdown
twin (:mod:`.html`), which answers go on which page (:mod:`.pages`) and the field picture of
a solved state (:mod:`.fields`)."""

from .answer_rows import fatigue_rows, summary_rows
from .design import (
                     arc_stress_plot,
                     default_design_report,
                     markdown_summary,
                     torque_plot,
                     torque_speed_plot,
                     write_analysis,
)
from .fields import field_picture
from .guideline_charts import draw_guideline_charts, elasticity_chart, guideline_table, oat_chart, short_method
from .html import Figure, Page, Table, Text, folder_page, render_html, render_md, write_page
from .pages import (
                     compensation_page,
                     design_page,
                     design_verdicts,
                     optimization_page,
                     param_table,
                     tolerance_page,
)
from .runs import compensation_report, optimization_report, slip_heat_files, tolerance_report, write_report
from .study_charts import answers_vs_inputs, draw_study_charts, parallel_coordinates, shortfall
from .target_charts import (
                     compensation_convergence,
                     compensation_profile,
                     compensation_torque,
                     optimization_path,
                     tolerance_histograms,
                     tolerance_ranking,
                     tolerance_text,
)

__all__ = ["Figure", "Page", "Table", "Text", "answers_vs_inputs", "arc_stress_plot", "compensation_convergence",
           "compensation_page", "compensation_profile", "compensation_report", "compensation_torque",
           "default_design_report", "design_page", "design_verdicts", "draw_guideline_charts", "draw_study_charts",
           "elasticity_chart", "fatigue_rows", "field_picture", "folder_page", "guideline_table", "markdown_summary",
           "oat_chart", "optimization_page", "optimization_path", "optimization_report", "parallel_coordinates",
           "param_table", "render_html", "render_md", "short_method", "shortfall", "slip_heat_files",
           "summary_rows", "tolerance_histograms", "tolerance_page", "tolerance_ranking", "tolerance_report",
           "tolerance_text", "torque_plot", "torque_speed_plot", "write_analysis", "write_page", "write_report"]

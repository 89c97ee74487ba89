"""Report stage: designer-facing output of analysed designs and design-to-targets runs:
plots (:mod:`.design`), the summary table (:mod:`.answer_rows`), the self-contained HTML page and its Markdown
twin (:mod:`.html`), which answers go on which page (:mod:`.pages`) and the field picture of
a solved state (:mod:`.fields`)."""

from ..core import lazy_names

#: public name -> the module of this package it lives in (imported on first use: PEP 562; the
#: summary table's rows load no plotting library)
_NAMES: dict[str, str] = {
    "answers_vs_inputs": "study_charts",
    "arc_stress_plot": "design",
    "compensation_convergence": "target_charts",
    "compensation_page": "pages",
    "compensation_profile": "target_charts",
    "compensation_report": "runs",
    "compensation_torque": "target_charts",
    "default_design_report": "design",
    "design_page": "pages",
    "design_verdicts": "pages",
    "draw_guideline_charts": "guideline_charts",
    "draw_study_charts": "study_charts",
    "elasticity_chart": "guideline_charts",
    "fatigue_rows": "answer_rows",
    "field_picture": "fields",
    "Figure": "html",
    "folder_page": "html",
    "guideline_table": "guideline_charts",
    "markdown_summary": "design",
    "oat_chart": "guideline_charts",
    "optimization_page": "pages",
    "optimization_path": "target_charts",
    "optimization_report": "runs",
    "Page": "html",
    "parallel_coordinates": "study_charts",
    "param_table": "pages",
    "render_html": "html",
    "render_md": "html",
    "short_method": "guideline_charts",
    "shortfall": "study_charts",
    "slip_heat_files": "runs",
    "summary_rows": "answer_rows",
    "Table": "html",
    "Text": "html",
    "tolerance_histograms": "target_charts",
    "tolerance_page": "pages",
    "tolerance_ranking": "target_charts",
    "tolerance_report": "runs",
    "tolerance_text": "target_charts",
    "torque_plot": "design",
    "torque_speed_plot": "design",
    "write_analysis": "design",
    "write_page": "html",
    "write_report": "runs",
}

__all__ = ["Figure", "Page", "Table", "Text", "answers_vs_inputs", "arc_stress_plot", "compensation_convergence",
           "compensation_page", "compensation_profile", "compensation_report", "compensation_torque",
           "default_design_report", "design_page", "design_verdicts", "draw_guideline_charts", "draw_study_charts",
           "elasticity_chart", "fatigue_rows", "field_picture", "folder_page", "guideline_table", "markdown_summary",
           "oat_chart", "optimization_page", "optimization_path", "optimization_report", "parallel_coordinates",
           "param_table", "render_html", "render_md", "short_method", "shortfall", "slip_heat_files",
           "summary_rows", "tolerance_histograms", "tolerance_page", "tolerance_ranking", "tolerance_report",
           "tolerance_text", "torque_plot", "torque_speed_plot", "write_analysis", "write_page", "write_report"]

__getattr__, __dir__ = lazy_names(__name__, globals(), _NAMES)

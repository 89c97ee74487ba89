"""Design to targets (issue 11): shoe-profile compensation, optimisation, tolerance Monte
Carlo and the one-page report.

* :mod:`.evaluate`: one design point -> one row of answers; :func:`~.evaluate.evaluate_many`
  is the only place where batches of designs are evaluated (a local process pool, each
  design in its own forked process: a gmsh abort kills one evaluation, not the run);
* :mod:`.compensate`: the table profile that spreads the contact pressure evenly over a
  target share of the shoe at one speed;
* :mod:`.optimize`: targets (the requirement checks) and a derivative-free search;
* :mod:`.tolerance`: Monte Carlo of manufacturing tolerances, share out of spec, ranking;
* :mod:`.page`: the self-contained HTML page and its Markdown twin.
"""

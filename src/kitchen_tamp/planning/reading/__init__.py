"""Reading PDDL files into plain records, and the caches that spare a run the reading.

Two readers meet in the records of ``syntax``: ``strips_text_reader`` reads the
STRIPS fragment straight from the text (no Lark, no ``pddl`` package: the fast
start-up path), and ``package_reader`` reads everything else with the ``pddl``
package, which also words every error. ``source`` reads a file and keeps its
text to place an error, ``grammar_cache`` keeps the package's Lark parsers and
``task_cache`` whole grounded tasks.
"""

"""Reading decks: MotionSolve XML (:mod:`.xml_reader`, data only) and Python statement scripts
(:mod:`.msolve`), the schema and attribute conversion (:mod:`.schema`), the expression language
(:mod:`.expr`), units (:mod:`.units`), and the checks that turn raw elements into a validated
:class:`~pysolver.model.Model` (:mod:`.validate`, :mod:`.bodies`, :mod:`.references`).
Entry points: :func:`pysolver.load`, :func:`pysolver.loads` (:mod:`.loader`).
"""

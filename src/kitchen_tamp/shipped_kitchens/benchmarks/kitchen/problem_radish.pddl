; The radish cooked, back on the tray (8 actions: to the sink, washed, onto the hob, cooked,
; back to the tray beside the other items).
(define (problem kitchen-radish)
  (:domain kitchen-regions)
  (:objects
    worktop tray plate - region
    sink - sink
    hob - burner
    cabbage glass radish - item)
  (:init
    (on cabbage tray)
    (on glass tray)
    (on radish tray)
    (clear cabbage)
    (clear glass)
    (clear radish)
    (handempty))
  (:goal (and
    (cooked radish)
    (on radish tray))))

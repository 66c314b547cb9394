; Cabbage cooked and on the plate, glass clean in the sink (11 actions): the cabbage goes from
; the tray to the sink, is washed, goes onto the hob, is cooked and goes onto the plate; the
; glass goes into the sink and is washed there.
(define (problem kitchen-cabbage-and-glass)
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
    (cooked cabbage)
    (on cabbage plate)
    (clean glass)
    (on glass sink))))

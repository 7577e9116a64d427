# The slow tier: scenario tests that take 5 s or more each on two cores (whole drapes and previews of library and
# real garments, renders of them). `ctest -LE slow` runs the rest, the fast tier, in a few minutes; `ctest` runs
# both. A gtest filter over all test executables: a name that an executable lacks matches nothing there.
set(DRAPE_SLOW_TESTS
  AvatarFeatureContact.DefaultSceneBodyDoesNotShowThroughTheShirt
  BroadTallBody.ShortDrapeOfTheFittedShirtIsLessStrained
  CliBatch.AKilledBatchKeepsItsFinishedDrapesAndTheRerunRunsOnlyTheRest
  CliBatchSlurm.*
  CliBench.ExtremesGridReportsEveryCellAndItsVerdict
  CliMakeAvatar.BuildsTheSameMannequinFromMeasurementsInEveryRun
  CliPlacement.ShirtOnABroaderTallerMannequinIsMovedWithAWarningPerPanel
  CliQuality.GarmentTooSmallForTheBodyFailsTheVerdictWithExitStatus4
  ExplodedState.EndsDivergedInEveryStageWithTheStateBeforeIt
  ExtremesGrid.LibraryTshirtHoldsInEveryCell
  Mannequin.MatchesTheRealMeanBodyOverTorsoAndLegs
  Mannequin.ShippedFemaleAndMaleMeasurementsFit
  NewtonContact.StretchedClothRestsWithinItsContactThickness
  NewtonRestConvergence.SkirtDrapeFromThePreviewComesToRest
  PdContactTarget.FrictionDoesNotLockTheLandingStretch
  PdTrousersPreview.HemsDoNotTearAtTheFeet
  PdTshirtPreview.*
  PipelineHandoff.LongerStepsAfterThePreviewSettleToNearlyTheSameDrape
  PipelineHandoff.StretchThatStaysExtremeDuringTheQuasiStaticStartIsATear
  PreviewFabric.SoftenedCottonTshirtPreviewStaysWholeWhereItsOwnStiffnessTears
  PreviewRetry.TornCottonPreviewStartsOverSofterFromThePlacedGarmentAndStaysWhole
  QuasiNewtonPreview.EveryFabricPresetSettlesAtTheLongStep
  QuasiNewtonPreview.NewtonsRestStateIsItsRestState
  RealGarmentDrape.GarmentPatternGeneratorSkirtMovedOntoMeanAllHangsFromTheWaist
  RealGarmentDrape.PencilDressOnGeneratedFemaleMannequin
  RealGarmentPipeline.GarmentCodeDenimShirtTornPreviewStartsOverWithTargetsFree
  RenderTest.NoBodyThroughTheDrapedGarmentCodeShirt
  RenderTest.NoBodyThroughTheDrapedTrousers)
list(JOIN DRAPE_SLOW_TESTS ":" DRAPE_SLOW_TEST_FILTER)

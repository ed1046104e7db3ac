"""Recording a run in MCAP (`morsec run --record run.mcap`): every stream's messages, each as its socket JSON
and, where ROS has a message for it, as the ROS 2 message the ROS middleware's table names (`channels`);
the loop only pickles each message and hands batches to a writer process (`recorder`), which converts them
(`ros2`, CDR through rosbags) and writes the file with the `mcap` package (`writer`). Nothing here is
imported by a run that does not record."""
